#include "geoshift/mesh.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"

namespace geoshift {
namespace {

// "face 3 (1, 1, 2), face 9 (4, 5, 4) and 10 more": enough to find them, short enough to read.
template <class Describe>
std::string listSome(const std::vector<int>& items, Describe describe, size_t shown = 5) {
  std::ostringstream s;
  for (size_t i = 0; i < items.size() && i < shown; ++i) s << (i ? ", " : "") << describe(items[i]);
  if (items.size() > shown) s << " and " << items.size() - shown << " more";
  return s.str();
}

std::string faceText(int index, const Face& f) {
  std::ostringstream s;
  s << "face " << index << " (" << f[0] << ", " << f[1] << ", " << f[2] << ")";
  return s.str();
}

void requireFinite(const std::vector<Vec3>& positions) {
  for (size_t v = 0; v < positions.size(); ++v) {
    const Vec3& p = positions[v];
    if (!p.allFinite()) {
      std::ostringstream s;
      s << "vertex " << v << " has a non-finite coordinate (" << p.x() << ", " << p.y() << ", "
        << p.z() << ")";
      throw InputError(s.str());
    }
  }
}

// A face's area takes its edges' lengths to the fourth power, which overflows double precision
// beyond about 1e77 and underflows below about 1e-77: a mesh whose faces span more than 1e75 or
// less than 1e-75 (its used vertices' bounding box, longest side) is refused with its size, rather
// than read as all degenerate or filtered with infinite areas. docs/denoising.md#bad-input.
void requireRepresentableSize(const std::vector<Vec3>& positions, const std::vector<Face>& faces) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Face& f : faces)
    for (int v : f) {
      lo = lo.cwiseMin(positions[v]);
      hi = hi.cwiseMax(positions[v]);
    }
  const double side = (hi - lo).maxCoeff();
  if (side > 1e75 || (side > 0 && side < 1e-75)) {
    std::ostringstream s;
    s << "the faces span " << side << " (the longest side of their bounding box): "
      << "areas and normals are computed in double precision for meshes between 1e-75 and 1e75 across; "
      << "scale the mesh " << (side > 1 ? "down" : "up");
    throw InputError(s.str());
  }
}

void requireValidFaces(const std::vector<Face>& faces, size_t vertexCount) {
  if (vertexCount == 0) throw InputError("empty mesh: no vertices");
  if (faces.empty()) throw InputError("no triangles: the mesh has vertices but no faces");
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = faces[f][k];
      if (i < 0 || static_cast<size_t>(i) >= vertexCount) {
        std::ostringstream s;
        s << "face " << f << ", corner " << k << ": vertex index " << i << " is out of range ("
          << vertexCount << " vertices)";
        throw InputError(s.str());
      }
    }
  }
}

// Twice the area is compared with the longest edge squared, so that the test is scale-free and
// only rejects faces whose corners are collinear up to round-off (needles are kept).
bool hasZeroArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double twiceArea = (b - a).cross(c - a).norm();
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !(twiceArea > 1e-12 * longest);
}

}  // namespace

Mesh::Mesh(std::vector<Vec3> positions, const std::vector<Face>& faces, BuildReport* report)
    : positions_(std::move(positions)) {
  requireValidFaces(faces, positions_.size());
  requireFinite(positions_);
  requireRepresentableSize(positions_, faces);
  BuildReport local;
  BuildReport& r = report ? *report : local;

  // --- degenerate faces: dropped, because no normal, angle or area is defined on them ---
  std::vector<int> repeated, zeroArea;
  faces_.reserve(faces.size());
  inputFace_.reserve(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    const Face& t = faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      repeated.push_back(static_cast<int>(f));
    } else if (hasZeroArea(positions_[t[0]], positions_[t[1]], positions_[t[2]])) {
      zeroArea.push_back(static_cast<int>(f));
    } else {
      faces_.push_back(t);
      inputFace_.push_back(static_cast<int>(f));
    }
  }
  auto describeInput = [&](int f) { return faceText(f, faces[f]); };
  r.repeatedIndexFaces = static_cast<int>(repeated.size());
  r.zeroAreaFaces = static_cast<int>(zeroArea.size());
  r.droppedFaces = repeated;
  r.droppedFaces.insert(r.droppedFaces.end(), zeroArea.begin(), zeroArea.end());
  std::sort(r.droppedFaces.begin(), r.droppedFaces.end());
  if (!repeated.empty())
    r.messages.push_back("dropped " + std::to_string(repeated.size()) +
                         " degenerate face(s) that use a vertex twice: " + listSome(repeated, describeInput));
  if (!zeroArea.empty())
    r.messages.push_back("dropped " + std::to_string(zeroArea.size()) +
                         " degenerate face(s) of zero area: " + listSome(zeroArea, describeInput));
  if (faces_.empty()) throw InputError("no valid triangles: all " + std::to_string(faces.size()) +
                                       " faces are degenerate");

  // --- twins: pair a->b with b->a; anything else on an edge is cut into boundary ---
  const int nh = halfedgeCount();
  twin_.assign(nh, -1);
  std::vector<std::pair<std::uint64_t, int>> edges(nh);
  for (int h = 0; h < nh; ++h) {
    const auto a = static_cast<std::uint64_t>(tail(h)), b = static_cast<std::uint64_t>(head(h));
    edges[h] = {std::min(a, b) << 32 | std::max(a, b), h};
  }
  std::sort(edges.begin(), edges.end());
  if (const std::vector<int> flipped = orientCoherently(edges); !flipped.empty()) {
    r.reorientedFaces = static_cast<int>(flipped.size());
    r.messages.push_back("re-oriented " + std::to_string(flipped.size()) +
                         " face(s) to agree with their neighbours (each piece keeps the orientation of most of its faces): " +
                         listSome(flipped, [&](int f) { return describeInput(inputFace(f)); }));
  }
  std::vector<std::pair<int, int>> badEdges;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    const size_t n = j - i;
    if (n == 2 && tail(edges[i].second) == head(edges[i + 1].second)) {
      twin_[edges[i].second] = edges[i + 1].second;
      twin_[edges[i + 1].second] = edges[i].second;
    } else if (n >= 2) {
      // More than two faces, or two faces that disagree on orientation. Keeping one consistent
      // pair keeps the surface connected through the most likely sheet; the rest become boundary.
      badEdges.push_back({tail(edges[i].second), head(edges[i].second)});
      for (size_t p = i; p < j; ++p) {
        for (size_t q = p + 1; q < j; ++q) {
          const int hp = edges[p].second, hq = edges[q].second;
          if (twin_[hp] < 0 && twin_[hq] < 0 && tail(hp) == head(hq)) {
            twin_[hp] = hq;
            twin_[hq] = hp;
            p = j;  // one pair only
            break;
          }
        }
      }
    }
    i = j;
  }
  r.nonManifoldEdges = static_cast<int>(badEdges.size());
  if (!badEdges.empty()) {
    std::vector<int> idx(badEdges.size());
    for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
    r.messages.push_back(
        "cut " + std::to_string(badEdges.size()) +
        " non-manifold edge(s) (more than two faces, or faces of opposite orientation): " +
        listSome(idx, [&](int i) {
          return "edge " + std::to_string(badEdges[i].first) + "-" + std::to_string(badEdges[i].second);
        }));
  }

  buildFans(r);
}

// Faces that disagree with a neighbour across an edge of exactly two faces (both run a->b; a face
// and its duplicate do not count) are flipped, so that such an edge is joined rather than cut.
// Faces joined by those edges form pieces; within a piece, which faces must flip relative to
// which is a parity kept by a union-find, and of its two consistent orientations the piece takes
// the one most of its faces already have (on a tie, that of its first face). A piece that cannot
// be oriented (a Moebius strip) keeps its first consistent assignment; the edges left in
// disagreement are cut as before. `edges` (sorted undirected keys with their half-edges) is
// updated for the flips. Returns the faces flipped, in index order. docs/denoising.md#bad-input.
std::vector<int> Mesh::orientCoherently(std::vector<std::pair<std::uint64_t, int>>& edges) {
  const int nf = faceCount();
  std::vector<int> parent(nf);
  std::vector<char> parity(nf, 0);  // of a face relative to its parent: 1 if exactly one of them flips
  for (int f = 0; f < nf; ++f) parent[f] = f;
  auto find = [&](int x) {
    int root = x;
    char p = 0;
    while (parent[root] != root) {
      p ^= parity[root];
      root = parent[root];
    }
    char toRoot = p;
    for (int y = x; parent[y] != root && parent[y] != y;) {
      const int next = parent[y];
      const char own = parity[y];
      parent[y] = root;
      parity[y] = toRoot;
      toRoot ^= own;
      y = next;
    }
    return std::pair<int, char>(root, p);
  };
  bool disagree = false;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    const int ha = edges[i].second, hb = edges[i + 1 < j ? i + 1 : i].second;
    // Two faces on the edge, not a face and its duplicate (the same corners: that edge stays cut).
    if (j - i == 2 && faces_[ha / 3][(ha % 3 + 2) % 3] != faces_[hb / 3][(hb % 3 + 2) % 3]) {
      const char d = tail(ha) == tail(hb);  // both run a->b: one of the two faces must flip
      disagree = disagree || d;
      auto [ra, pa] = find(ha / 3);
      auto [rb, pb] = find(hb / 3);
      if (ra != rb) {
        if (rb < ra) std::swap(ra, rb);
        parent[rb] = ra;  // the lower index is the root: a piece's root is its first face
        parity[rb] = static_cast<char>(pa ^ pb ^ d);
      }
    }
    i = j;
  }
  if (!disagree) return {};
  // Per root: the faces that differ from the root against those that agree with it. The root keeps
  // its orientation unless most of its piece differs from it.
  std::vector<int> balance(nf, 0);
  for (int f = 0; f < nf; ++f) {
    const auto [root, p] = find(f);
    balance[root] += p ? 1 : -1;
  }
  std::vector<int> flipped;
  for (int f = 0; f < nf; ++f) {
    const auto [root, p] = find(f);
    const bool invert = balance[root] > 0;  // most of the piece differs from its root: they stay
    if (p != invert) flipped.push_back(f);
  }
  if (flipped.empty()) return {};
  for (int f : flipped) {
    std::swap(faces_[f][1], faces_[f][2]);
    inputFace_[f] = -1 - inputFace_[f];  // inputFlipped(f)
  }
  // Face f's half-edge k joins the corners of its half-edge 2 - k before the flip, reversed.
  for (auto& [key, h] : edges)
    if (inputFlipped(h / 3)) h = 3 * (h / 3) + 2 - h % 3;
  std::sort(edges.begin(), edges.end());
  return flipped;
}

Mesh Mesh::withTwins(std::vector<Vec3> positions, std::vector<Face> faces, std::vector<int> twins,
                     BuildReport* report) {
  requireValidFaces(faces, positions.size());
  requireFinite(positions);
  for (size_t f = 0; f < faces.size(); ++f) {
    const Face& t = faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] ||
        hasZeroArea(positions[t[0]], positions[t[1]], positions[t[2]]))
      throw InputError("mesh with given twins: " + faceText(static_cast<int>(f), t) + " is degenerate");
  }
  const int nh = static_cast<int>(3 * faces.size());
  if (static_cast<int>(twins.size()) != nh)
    throw InputError("mesh with given twins: " + std::to_string(twins.size()) + " twins for " +
                     std::to_string(nh) + " half-edges");
  Mesh m;
  m.positions_ = std::move(positions);
  m.faces_ = std::move(faces);
  m.twin_ = std::move(twins);
  for (int h = 0; h < nh; ++h) {
    const int t = m.twin_[h];
    if (t < 0) {
      m.twin_[h] = -1;
      continue;
    }
    if (t >= nh || m.twin_[t] != h || m.tail(t) != m.head(h) || m.head(t) != m.tail(h))
      throw InputError("mesh with given twins: half-edge " + std::to_string(h) + " (" + std::to_string(m.tail(h)) +
                       " -> " + std::to_string(m.head(h)) + ") and its twin " + std::to_string(t) +
                       " are not an opposite pair");
  }
  m.inputFace_.resize(m.faces_.size());
  for (size_t f = 0; f < m.faces_.size(); ++f) m.inputFace_[f] = static_cast<int>(f);
  BuildReport local;
  m.buildFans(report ? *report : local);
  return m;
}

void Mesh::buildFans(BuildReport& r) {
  // --- vertex fans: a vertex whose faces form several fans is split, one copy per extra fan ---
  const int nh = halfedgeCount();
  const int nv0 = vertexCount();
  std::vector<int> outStart(nv0 + 1, 0), out(nh);
  for (int h = 0; h < nh; ++h) ++outStart[tail(h) + 1];
  for (int v = 0; v < nv0; ++v) outStart[v + 1] += outStart[v];
  {
    std::vector<int> fill(outStart.begin(), outStart.end() - 1);
    for (int h = 0; h < nh; ++h) out[fill[tail(h)]++] = h;
  }
  vertexHalfedge_.assign(nv0, -1);
  originalVertex_.resize(nv0);
  for (int v = 0; v < nv0; ++v) originalVertex_[v] = v;
  std::vector<char> visited(nh, 0);
  std::vector<int> splitVertices;
  std::vector<int> fan;
  for (int v = 0; v < nv0; ++v) {
    int fans = 0;
    const int degree = outStart[v + 1] - outStart[v];
    for (int i = outStart[v]; i < outStart[v + 1]; ++i) {
      const int h = out[i];
      if (visited[h]) continue;
      // Rotate clockwise to the fan's first half-edge (a boundary one), or all the way round.
      int start = h;
      for (int steps = 0; steps < degree; ++steps) {
        const int t = twin_[start];
        if (t < 0) break;
        const int cw = next(t);
        if (cw == h) break;
        start = cw;
      }
      fan.clear();
      int g = start;
      do {
        visited[g] = 1;
        fan.push_back(g);
        g = ccwOutgoing(g);
      } while (g >= 0 && g != start && static_cast<int>(fan.size()) <= degree);
      int target = v;
      if (fans > 0) {
        target = vertexCount();
        positions_.push_back(positions_[v]);
        originalVertex_.push_back(v);
        vertexHalfedge_.push_back(-1);
        for (int e : fan) faces_[e / 3][e % 3] = target;
      }
      vertexHalfedge_[target] = start;
      ++fans;
    }
    if (fans > 1) splitVertices.push_back(v);
  }
  r.nonManifoldVertices = static_cast<int>(splitVertices.size());
  r.splitVertexCopies = vertexCount() - nv0;
  if (!splitVertices.empty())
    r.messages.push_back("split " + std::to_string(splitVertices.size()) +
                         " non-manifold vertex(es) into one copy per fan of faces: " +
                         listSome(splitVertices, [](int v) { return "vertex " + std::to_string(v); }));

  std::vector<int> isolated;
  for (int v = 0; v < nv0; ++v)
    if (vertexHalfedge_[v] < 0) isolated.push_back(v);
  r.isolatedVertices = static_cast<int>(isolated.size());
  if (!isolated.empty())
    r.messages.push_back("kept " + std::to_string(isolated.size()) +
                         " isolated vertex(es) that no face uses; filters leave them as they are: " +
                         listSome(isolated, [](int v) { return "vertex " + std::to_string(v); }));
}

namespace {

// Moves block i of `a` (elements [B i, B i + B)) to block to[i] for every i, following the
// permutation's cycles in place. The entries of `to` are marked as their blocks move (complemented:
// ~k < 0) and restored at the end; nothing is allocated.
template <int B, class T>
void permuteInPlace(T* a, int* to, int n) noexcept {
  for (int i = 0; i < n; ++i) {
    if (to[i] < 0) continue;
    std::array<T, B> carry;  // the block that waits for its place
    std::copy_n(a + B * i, B, carry.begin());
    for (int j = i;;) {
      const int k = to[j];
      to[j] = ~k;
      if (k == i) {
        std::copy_n(carry.begin(), B, a + B * i);
        break;
      }
      std::swap_ranges(carry.begin(), carry.end(), a + B * k);  // block k in place; its old one goes next
      j = k;
    }
  }
  for (int i = 0; i < n; ++i) to[i] = ~to[i];
}

bool isPermutation(const std::vector<int>& p, int n) {
  if (static_cast<int>(p.size()) != n) return false;
  std::vector<char> seen(n, 0);
  for (int i : p) {
    if (i < 0 || i >= n || seen[i]) return false;
    seen[i] = 1;
  }
  return true;
}

}  // namespace

void Mesh::renumber(Renumbering& r) noexcept {
  const int nv = vertexCount(), nf = faceCount();
  int* newVertex = r.newVertex.data();
  const bool byInput = r.newFace.empty();
  auto faceTo = [&](int f) { return byInput ? inputFace(f) : r.newFace[f]; };
  auto newHalfedge = [&](int h) { return h < 0 ? h : 3 * faceTo(h / 3) + h % 3; };
  // The values first, while every face is still where faceTo reads it.
  for (Face& t : faces_)
    for (int& v : t) v = newVertex[v];
  for (int& h : twin_) h = newHalfedge(h);
  for (int& h : vertexHalfedge_) h = newHalfedge(h);
  for (int& v : originalVertex_) v = newVertex[v];
  permuteInPlace<1>(positions_.data(), newVertex, nv);
  permuteInPlace<1>(vertexHalfedge_.data(), newVertex, nv);
  permuteInPlace<1>(originalVertex_.data(), newVertex, nv);
  if (!byInput) {
    int* newFace = r.newFace.data();
    permuteInPlace<1>(faces_.data(), newFace, nf);
    permuteInPlace<1>(inputFace_.data(), newFace, nf);
    permuteInPlace<3>(twin_.data(), newFace, nf);  // a face's three half-edges move together
    return;
  }
  // Each face to inputFace(f), which moves with it: every swap puts one face where it belongs, and a
  // place already taken is never swapped again, so this ends after at most nf swaps whatever the
  // input faces are (one past the last face stays where it is).
  for (int g = 0; g < nf; ++g)
    for (int d = inputFace(g); d != g && d < nf && inputFace(d) != d; d = inputFace(g)) {
      std::swap(faces_[g], faces_[d]);
      std::swap(inputFace_[g], inputFace_[d]);
      std::swap_ranges(twin_.begin() + 3 * g, twin_.begin() + 3 * g + 3, twin_.begin() + 3 * d);
    }
}

bool isRenumbering(const Mesh& mesh, const Renumbering& r) {
  return isPermutation(r.newVertex, mesh.vertexCount()) && isPermutation(r.newFace, mesh.faceCount());
}

void invert(Renumbering& r) noexcept {
  // Inverse of a permutation in place: along each cycle i → p[i] → ..., p[p[i]] = i; visited
  // entries are complemented and restored at the end.
  for (std::vector<int>* p : {&r.newVertex, &r.newFace}) {
    int* a = p->data();
    const int n = static_cast<int>(p->size());
    for (int i = 0; i < n; ++i) {
      if (a[i] < 0) continue;
      int from = i, at = a[i];
      while (at != i) {
        const int next = a[at];
        a[at] = ~from;
        from = at;
        at = next;
      }
      a[i] = ~from;
    }
    for (int i = 0; i < n; ++i) a[i] = ~a[i];
  }
}

std::vector<int> mortonOrder(const Mesh& mesh) {
  const int nv = mesh.vertexCount();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : mesh.positions())
    if (p.allFinite()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const auto spread = [](std::uint64_t x) {  // 21 bits to every third of 63
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  };
  std::vector<std::pair<std::uint64_t, int>> key(nv);
  for (int v = 0; v < nv; ++v) {
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double ext = hi[a] - lo[a], x = mesh.position(v)[a];
      double q = ext > 0 ? (x - lo[a]) / ext * 2097151.0 : 0.0;
      if (!(q >= 0)) q = 0;  // also NaN
      code |= spread(static_cast<std::uint64_t>(std::min(q, 2097151.0))) << a;
    }
    key[v] = {code, v};
  }
  std::sort(key.begin(), key.end());
  std::vector<int> order(nv);
  for (int i = 0; i < nv; ++i) order[key[i].second] = i;
  return order;
}

Renumbering spatialOrder(const Mesh& mesh) {
  const int nv = mesh.vertexCount(), nf = mesh.faceCount();
  Renumbering r;
  r.newVertex = mortonOrder(mesh);
  // Faces by their lowest new corner: a counting sort, stable in index order.
  std::vector<int> start(nv + 1, 0);
  auto lowest = [&](int f) {
    const Face& t = mesh.face(f);
    return std::min({r.newVertex[t[0]], r.newVertex[t[1]], r.newVertex[t[2]]});
  };
  for (int f = 0; f < nf; ++f) ++start[lowest(f) + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  r.newFace.resize(nf);
  for (int f = 0; f < nf; ++f) r.newFace[f] = start[lowest(f)]++;
  return r;
}

std::vector<int> Mesh::neighbors(int v) const {
  std::vector<int> result;
  int last = -1;
  forEachOutgoing(v, [&](int h) {
    result.push_back(head(h));
    last = h;
  });
  // On the boundary the last face's other edge leads to the second boundary neighbour.
  if (last >= 0 && twin_[prev(last)] < 0) result.push_back(tail(prev(last)));
  return result;
}

std::vector<std::vector<int>> Mesh::boundaryLoops() const {
  std::vector<std::vector<int>> loops;
  std::vector<char> seen(halfedgeCount(), 0);
  for (int h0 = 0; h0 < halfedgeCount(); ++h0) {
    if (twin_[h0] >= 0 || seen[h0]) continue;
    std::vector<int> loop;
    int h = h0;
    while (h >= 0 && !seen[h]) {
      seen[h] = 1;
      loop.push_back(tail(h));
      // After fan splitting each boundary vertex has exactly one outgoing boundary half-edge.
      h = vertexHalfedge_[head(h)];
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

// --- welding ---------------------------------------------------------------------------------

namespace {

struct KeyHash {
  size_t operator()(const std::array<std::int64_t, 3>& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (auto x : k) {
      h ^= static_cast<std::uint64_t>(x) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
      h *= 1099511628211ull;
    }
    // size_t is 32 bits in wasm: fold the high half in, or float-derived doubles (low mantissa bits
    // all zero) share one bucket and welding turns quadratic.
    return static_cast<size_t>(h ^ (h >> 32));
  }
};

std::int64_t bitsOf(double x) {
  if (x == 0.0) x = 0.0;  // -0 and +0 are the same position
  std::int64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

}  // namespace

Weld weld(const std::vector<Vec3>& positions, const WeldOptions& options) {
  requireFinite(positions);
  requireFinite("weld tolerance", options.tolerance);
  Weld w;
  w.vertexOf.resize(positions.size());
  std::unordered_map<std::array<std::int64_t, 3>, int, KeyHash> cells;
  cells.reserve(positions.size());
  const double tol = options.tolerance;
  for (size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    int found = -1;
    if (tol <= 0) {
      auto [it, inserted] = cells.try_emplace({bitsOf(p.x()), bitsOf(p.y()), bitsOf(p.z())},
                                              static_cast<int>(w.positions.size()));
      if (!inserted) found = it->second;
    } else {
      // Grid of cell size tol: any partner within tol lies in one of the 27 surrounding cells.
      // A cell keeps the first welded vertex that fell into it.
      // Cell indices are clamped to +-2^62 (converting a larger double to an integer is undefined,
      // and the neighbours' +-1 must not overflow): positions that far out in tolerances share the
      // outermost cells, where only the distance test below decides.
      auto cell = [&](double x) {
        constexpr double kMaxCell = 4611686018427387904.0;  // 2^62
        return static_cast<std::int64_t>(std::clamp(std::floor(x / tol), -kMaxCell, kMaxCell));
      };
      const std::array<std::int64_t, 3> c = {cell(p.x()), cell(p.y()), cell(p.z())};
      double best = tol;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
            if (it == cells.end()) continue;
            const double d = (w.positions[it->second] - p).norm();
            if (d <= best) {
              best = d;
              found = it->second;
            }
          }
      if (found < 0) cells.try_emplace(c, static_cast<int>(w.positions.size()));
    }
    if (found >= 0) {
      w.vertexOf[i] = found;
      ++w.mergedCount;
    } else {
      w.vertexOf[i] = static_cast<int>(w.positions.size());
      w.positions.push_back(p);
    }
  }
  return w;
}

MeshBuild buildMesh(const TriangleSoup& soup, const MeshBuildOptions& options) {
  // Validate in the caller's numbering, before welding renumbers anything.
  requireValidFaces(soup.faces, soup.positions.size());
  requireFinite(soup.positions);

  MeshBuild result;
  BuildReport& r = result.report;
  r.inputVertices = static_cast<int>(soup.positions.size());
  r.inputFaces = static_cast<int>(soup.faces.size());

  std::vector<Vec3> positions;
  if (options.weld) {
    Weld w = weld(soup.positions, options.weldOptions);
    positions = std::move(w.positions);
    result.vertexOf = std::move(w.vertexOf);
    r.weldedVertices = w.mergedCount;
  } else {
    positions = soup.positions;
    result.vertexOf.resize(soup.positions.size());
    for (size_t i = 0; i < result.vertexOf.size(); ++i) result.vertexOf[i] = static_cast<int>(i);
  }
  std::vector<Face> faces(soup.faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) faces[f][k] = result.vertexOf[soup.faces[f][k]];

  result.mesh = Mesh(std::move(positions), faces, &r);

  // A caller vertex of a split vertex belongs to the piece its own faces went to. One whose faces
  // went to several pieces (one index shared by a surface and a fin cut off it) belongs to the
  // piece that holds most of them, the lower vertex on a tie (the original before its copies): a
  // caller vertex has one position to write back, and a small piece must not move the surface's.
  const Mesh& m = result.mesh;
  std::vector<char> severalPieces(soup.positions.size(), 0);
  std::vector<int> first(soup.positions.size(), -1);
  for (int f = 0; f < m.faceCount(); ++f) {
    const Face& caller = soup.faces[m.inputFace(f)];
    for (int k = 0; k < 3; ++k) {
      const int c = caller[m.inputCorner(f, k)];
      int& at = first[c];
      if (at < 0) at = m.face(f)[k];
      if (at != m.face(f)[k]) severalPieces[c] = 1;
    }
  }
  std::vector<std::pair<int, int>> incidences;  // (caller vertex, mesh vertex), for those with several pieces
  for (int f = 0; f < m.faceCount(); ++f) {
    const Face& caller = soup.faces[m.inputFace(f)];
    for (int k = 0; k < 3; ++k) {
      const int c = caller[m.inputCorner(f, k)];
      if (severalPieces[c]) incidences.emplace_back(c, m.face(f)[k]);
      else result.vertexOf[c] = m.face(f)[k];
    }
  }
  std::sort(incidences.begin(), incidences.end());
  for (size_t i = 0; i < incidences.size();) {
    const int c = incidences[i].first;
    int best = -1, bestCount = 0;
    while (i < incidences.size() && incidences[i].first == c) {
      size_t j = i;
      while (j < incidences.size() && incidences[j] == incidences[i]) ++j;
      if (static_cast<int>(j - i) > bestCount) {  // ascending vertices: a tie keeps the lower
        best = incidences[i].second;
        bestCount = static_cast<int>(j - i);
      }
      i = j;
    }
    result.vertexOf[c] = best;
  }
  return result;
}

Pieces pieces(const Mesh& mesh) {
  const int nv = mesh.vertexCount();
  // Union-find over the faces' vertices, each root the lowest vertex of its set.
  std::vector<int> parent(nv);
  for (int v = 0; v < nv; ++v) parent[v] = v;
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Face& f : mesh.faces())
    for (int k = 1; k < 3; ++k) {
      const int a = root(f[0]), b = root(f[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  Pieces out;
  out.pieceOf.assign(nv, -1);
  std::vector<int> numberOf(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (mesh.isIsolated(v)) continue;
    int& n = numberOf[root(v)];
    if (n < 0) {
      n = static_cast<int>(out.vertexCount.size());
      out.vertexCount.push_back(0);
    }
    out.pieceOf[v] = n;
    ++out.vertexCount[n];
  }
  return out;
}

std::vector<double> toCallerLayout(const std::vector<double>& meshValues, int dim,
                                   const std::vector<int>& vertexOf) {
  std::vector<double> out(vertexOf.size() * dim);
  for (size_t i = 0; i < vertexOf.size(); ++i)
    for (int d = 0; d < dim; ++d) out[i * dim + d] = meshValues[static_cast<size_t>(vertexOf[i]) * dim + d];
  return out;
}

std::vector<double> toMeshLayout(const std::vector<double>& callerValues, int dim,
                                 const std::vector<int>& vertexOf, const Mesh& mesh,
                                 bool unitVectors) {
  const int n = mesh.vertexCount();
  std::vector<double> sum(static_cast<size_t>(n) * dim, 0.0);
  std::vector<int> count(n, 0);
  for (size_t i = 0; i < vertexOf.size(); ++i) {
    const int v = vertexOf[i];
    ++count[v];
    for (int d = 0; d < dim; ++d) sum[static_cast<size_t>(v) * dim + d] += callerValues[i * dim + d];
  }
  // Split copies whose caller vertices all went to another piece of the same original vertex
  // take that piece's value.
  std::vector<int> donor(n, -1);
  for (int v = 0; v < n; ++v) {
    double* row = sum.data() + static_cast<size_t>(v) * dim;
    if (count[v] > 1)
      for (int d = 0; d < dim; ++d) row[d] /= count[v];
    if (count[v] > 0 && donor[mesh.originalVertex(v)] < 0) donor[mesh.originalVertex(v)] = v;
  }
  for (int v = 0; v < n; ++v) {
    const int from = donor[mesh.originalVertex(v)];
    if (count[v] > 0 || from < 0) continue;
    for (int d = 0; d < dim; ++d)
      sum[static_cast<size_t>(v) * dim + d] = sum[static_cast<size_t>(from) * dim + d];
  }
  // Averaging first keeps the mean direction; normalising then puts it back on the sphere.
  if (unitVectors) {
    for (int v = 0; v < n; ++v) {
      double* row = sum.data() + static_cast<size_t>(v) * dim;
      double len = 0;
      for (int d = 0; d < dim; ++d) len += row[d] * row[d];
      len = std::sqrt(len);
      if (len > 0)
        for (int d = 0; d < dim; ++d) row[d] /= len;
    }
  }
  return sum;
}

}  // namespace geoshift

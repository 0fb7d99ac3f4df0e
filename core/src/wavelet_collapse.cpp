// Half-edge collapses in place for the wavelet analysis (wavelet_detail.hpp).
#include <algorithm>
#include <stdexcept>

#include "wavelet_detail.hpp"

namespace geoshift::wavelet_detail {

CollapseMesh::CollapseMesh(const Mesh& mesh)
    : faces_(mesh.faces()), twin_(mesh.halfedgeCount()), vh_(mesh.vertexCount()), mark_(mesh.vertexCount(), 0) {
  for (int h = 0; h < mesh.halfedgeCount(); ++h) twin_[h] = mesh.twin(h);
  for (int v = 0; v < mesh.vertexCount(); ++v) vh_[v] = mesh.halfedge(v);
}

void CollapseMesh::ring(int v, Ring& r) const {
  r.vertex.clear();
  r.outgoing.clear();
  r.boundary = false;
  const int start = vh_[v];
  if (start < 0) return;
  int h = start;
  do {
    r.outgoing.push_back(h);
    r.vertex.push_back(head(h));
    const int p = prev(h);
    h = twin_[p];
    if (h < 0) {
      r.vertex.push_back(tail(p));
      r.boundary = true;
      return;
    }
  } while (h != start);
}

bool CollapseMesh::canCollapse(int o, const Ring& r, int j, const PositionRows& x, double cosMax) {
  const int k = r.faces();
  const int n = static_cast<int>(r.vertex.size());
  if (k < 1 || (!r.boundary && k < 3)) return false;
  if (r.boundary && j != 0 && j != n - 1) return false;
  const int t = r.vertex[j];

  // Link condition: the common neighbours of o and t are exactly the apexes of the faces on (o, t).
  if (++markValue_ == 0) {
    std::fill(mark_.begin(), mark_.end(), 0);
    markValue_ = 1;
  }
  for (int v : r.vertex) mark_[v] = markValue_;
  ring(t, scratch_);
  int common = 0;
  for (int v : scratch_.vertex) common += mark_[v] == markValue_;
  const int apexes = r.boundary ? 1 : 2;
  if (common != apexes) return false;

  if (r.boundary) {
    // A lone triangle (o, t, w) with o-w and t-w both on the boundary would leave a dangling edge.
    // In the face on (o, t) the half-edge after o -> t (j = 0) or after o -> w (j = last) joins t and w.
    const bool ow = k == 1;
    const bool tw = twin_[next(j == 0 ? r.outgoing[0] : r.outgoing[k - 1])] < 0;
    if (ow && tw) return false;
  } else if (k == 3) {
    // Valence three: the surviving face (t, a, b) must not exist already on the other side of a-b.
    const int keep = (j + 1) % 3;
    const int hab = next(r.outgoing[keep]);
    const int across = twin_[hab];
    if (across >= 0 && head(next(across)) == t) return false;
  }

  // No surviving face of o's fan may flip, turn too far or become degenerate.
  const int before = r.boundary ? j - 1 : (j + k - 1) % k;
  const Vec3 xo = x(o), xt = x(t);
  for (int i = 0; i < k; ++i) {
    if (i == j || i == before) continue;
    const Vec3 a = x(r.vertex[i]), b = x(r.vertex[r.next(i)]);
    const Vec3 oldCross = (a - xo).cross(b - xo);
    const Vec3 newCross = (a - xt).cross(b - xt);
    const double newNorm = newCross.norm();
    const double longest = std::max({(a - xt).squaredNorm(), (b - xt).squaredNorm(), (b - a).squaredNorm()});
    if (!(newNorm > 1e-6 * longest)) return false;
    if (!(newCross.dot(oldCross) > cosMax * newNorm * oldCross.norm())) return false;
  }
  return true;
}

void CollapseMesh::setHalfedge(int v, int h) {
  if (vh_[v] == h) return;
  vhLog_.emplace_back(v, vh_[v]);
  vh_[v] = h;
}

// After a collapse: keep v's half-edge if it survived (collapses keep every remaining vertex's
// boundary status, and a boundary half-edge stays one), else take a live outgoing one from the
// candidates, turned clockwise onto the boundary for a boundary vertex.
void CollapseMesh::repairHalfedge(int v, bool boundary, const std::vector<int>& candidates) {
  const int old = vh_[v];
  if (old >= 0 && faceAlive(old / 3) && (!boundary || twin_[old] < 0)) return;
  int hint = -1;
  for (int h : candidates)
    if (h >= 0 && faceAlive(h / 3) && tail(h) == v) {
      hint = h;
      break;
    }
  if (hint < 0 || !boundary) {
    setHalfedge(v, hint);
    return;
  }
  int h = hint;
  for (;;) {
    const int t = twin_[h];
    if (t < 0) break;
    const int cw = next(t);
    if (cw == hint) break;
    h = cw;
  }
  setHalfedge(v, h);
}

void CollapseMesh::collapseTopology(int o, const Ring& r, int j) {
  const int k = r.faces();
  const int t = r.vertex[j];
  const int before = r.boundary ? j - 1 : (j + k - 1) % k;
  int dead[2] = {-1, -1};
  if (j < k) dead[0] = r.outgoing[j] / 3;
  if (before >= 0) dead[1] = r.outgoing[before] / 3;

  candidates_.clear();
  int apexes[2] = {-1, -1};
  bool apexBoundary[2] = {false, false};
  int outer[2][2] = {{-1, -1}, {-1, -1}};
  const bool targetBoundary = twin_[vh_[t]] < 0;
  // Each dead face (o, t, w): its edges t-w and w-o merge into one, so their outer half-edges become twins.
  for (int side = 0; side < 2; ++side) {
    const int f = dead[side];
    if (f < 0) continue;
    int htw = -1, hwo = -1, w = -1;
    for (int c = 0; c < 3; ++c) {
      const int h = 3 * f + c;
      const int a = tail(h), b = head(h);
      if (a != o && b != o) {
        htw = h;
        w = a == t ? b : a;
      } else if (a != t && b != t) {
        hwo = h;
      }
    }
    apexes[side] = w;
    outer[side][0] = htw;
    outer[side][1] = hwo;
  }
  // Boundary status before any twin changes (a merged edge may turn a half-edge into a boundary one).
  for (int side = 0; side < 2; ++side)
    if (apexes[side] >= 0) apexBoundary[side] = twin_[vh_[apexes[side]]] < 0;
  for (int side = 0; side < 2; ++side) {
    if (dead[side] < 0) continue;
    const int htw = outer[side][0], hwo = outer[side][1];
    const int outer1 = twin_[htw], outer2 = twin_[hwo];
    if (outer1 >= 0) twin_[outer1] = outer2;
    if (outer2 >= 0) twin_[outer2] = outer1;
    for (int h : {outer1, outer2})
      if (h >= 0) {
        candidates_.push_back(h);
        candidates_.push_back(next(h));
      }
  }
  for (int f : dead) {
    if (f < 0) continue;
    faces_[f] = {-1, -1, -1};
    for (int c = 0; c < 3; ++c) twin_[3 * f + c] = -1;
  }
  for (int i = 0; i < k; ++i) {
    const int f = r.outgoing[i] / 3;
    if (f == dead[0] || f == dead[1]) continue;
    for (int c = 0; c < 3; ++c)
      if (faces_[f][c] == o) faces_[f][c] = t;
    candidates_.push_back(r.outgoing[i]);  // now leaves t
  }
  setHalfedge(o, -1);
  repairHalfedge(t, targetBoundary, candidates_);
  for (int side = 0; side < 2; ++side)
    if (apexes[side] >= 0) repairHalfedge(apexes[side], apexBoundary[side], candidates_);
}

void CollapseMesh::beginLevel() {
  savedFaces_ = faces_;
  savedTwin_ = twin_;
  vhLog_.clear();
}

void CollapseMesh::rollback() {
  faces_ = savedFaces_;
  twin_ = savedTwin_;
  for (auto it = vhLog_.rbegin(); it != vhLog_.rend(); ++it) vh_[it->first] = it->second;
  vhLog_.clear();
}

std::vector<int> CollapseMesh::compact(const std::vector<int>& liveVertices) {
  std::vector<int> newIndex(faces_.size(), -1), parent;
  parent.reserve(faces_.size());
  for (int f = 0; f < faceCount(); ++f)
    if (faceAlive(f)) {
      newIndex[f] = static_cast<int>(parent.size());
      parent.push_back(f);
    }
  // In place: a face only moves down, onto a face already read.
  for (size_t nf = 0; nf < parent.size(); ++nf) {
    const int f = parent[nf];
    faces_[nf] = faces_[f];
    for (int c = 0; c < 3; ++c) {
      const int t = twin_[3 * f + c];
      twin_[3 * nf + c] = t < 0 ? -1 : 3 * newIndex[t / 3] + t % 3;
    }
  }
  faces_.resize(parent.size());
  twin_.resize(3 * parent.size());
  for (int v : liveVertices) {
    const int h = vh_[v];
    if (h >= 0) {
      if (newIndex[h / 3] < 0) throw std::logic_error("wavelet: a live vertex points into a collapsed face");
      vh_[v] = 3 * newIndex[h / 3] + h % 3;
    }
  }
  return parent;
}

}  // namespace geoshift::wavelet_detail

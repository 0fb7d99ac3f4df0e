// Log map by discrete geodesic polar coordinates (Melvær–Reimers 2012; docs/algorithms.md#log-map).
//
// A Dijkstra-like front: each popped vertex c updates the two other corners of every face around
// it by unfolding the face onto the plane together with a virtual source σ placed at distances
// (U_j, U_k) from the edge's ends. Angles are interpolated between the edge's ends.
//
// Boundaries: faces are only traversed where they exist, so on a convex (or flat-bounded) patch the
// result is exact in the plane; vertices that hide behind a concave boundary are reached around it
// by the same unfolding and the fallbacks, which gives a distance along the boundary-hugging path
// and an angle interpolated from the vertices that carried it: whatever DGPC gives, not a true
// polar coordinate. Isolated vertices are never reached.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "logmap_detail.hpp"

namespace geoshift {

using namespace logmap_detail;  // private to this file and logmap_detail.hpp

// What every solver of one mesh reads and none writes: built once, shared by LogMap::fork().
struct LogMap::Tables {
  // The solver works in its own vertex numbering, sorted along a Morton curve of the positions, so
  // that a front (a small disc of the surface) reads a few runs of neighbouring values and rings
  // instead of lines scattered over a large mesh. Mesh ids go in only at the seeds (inner) and come
  // back only in the output (Ring::meshVertex).
  std::vector<int> inner;
  // Each vertex's ring, by internal vertex: its neighbours counter-clockwise from the head of
  // halfedge(v), as the run() loop visits its faces. Rings of more than kInlineSlots neighbours
  // keep them in the overflow arrays.
  std::vector<Ring> ring;
  std::vector<std::int32_t> overflowIds;
  std::vector<RingSlot> overflowSlots;

  explicit Tables(const SurfaceGeometry& g) {
    const Mesh& mesh = g.mesh();
    const int nv = mesh.vertexCount(), nf = mesh.faceCount();
    ring.resize(nv);
    renumber(mesh);
    std::vector<double> twiceArea(nf);
    for (int f = 0; f < nf; ++f) twiceArea[f] = faceRecord(g, f).twiceArea;
    std::vector<std::int32_t> ids;
    std::vector<RingSlot> slots;
    for (int c = 0; c < nv; ++c) {
      Ring& r = ring[c];
      const int start = mesh.halfedge(r.meshVertex);
      if (start < 0) continue;  // isolated: never reached
      ids.clear();
      slots.clear();
      int h = start;
      do {
        const int prev = Mesh::prev(h);
        ids.push_back(inner[mesh.head(h)]);
        slots.push_back({g.length(h), 0.5 / g.length(h), g.length(Mesh::next(h)), twiceArea[h / 3]});
        h = mesh.ccwOutgoing(h);
        if (h < 0) {  // past the last face: its apex ends the open ring
          ids.push_back(inner[mesh.tail(prev)]);
          slots.push_back({g.length(prev), 0.5 / g.length(prev), 0.0, 0.0});
          r.open = 1;
        }
      } while (h >= 0 && h != start);
      r.slots = static_cast<int>(ids.size());
      if (r.slots <= kInlineSlots) {
        std::copy(ids.begin(), ids.end(), r.n);
        std::copy(slots.begin(), slots.end(), r.s);
      } else {
        r.overflow = static_cast<int>(overflowIds.size());
        overflowIds.insert(overflowIds.end(), ids.begin(), ids.end());
        overflowSlots.insert(overflowSlots.end(), slots.begin(), slots.end());
      }
    }
  }

  // The Morton order of the positions (mortonOrder in mesh.hpp).
  void renumber(const Mesh& mesh) {
    inner = mortonOrder(mesh);
    for (int v = 0; v < mesh.vertexCount(); ++v) ring[inner[v]].meshVertex = v;
  }
};

// One solver's mutable buffers: values by internal vertex, the heap, the output.
struct LogMap::State {
  const Mesh& mesh;
  const std::vector<int>& inner;
  const Tables& tables;
  // U and Θ of a vertex side by side: an update reads both of its edge's ends.
  struct Value {
    double U, theta;
  };
  std::vector<Value> value;                     // by internal vertex
  std::vector<int> touched;                     // internal vertices with a finite U, reset by the next call
  // Binary min-heap on U with lazy deletion: `queued` entries, then one +inf entry so that a
  // last parent's right child always exists.
  std::vector<Queued> heap{Queued{kInf, -1}};
  size_t queued = 0;
  std::vector<int> pending;                     // ring faces of c that had no known corner yet
  std::vector<DeferredAngle> deferred;          // a pending Θ is stored as −1 − its index here
  std::vector<Queued> popped;                   // valid pops within R, in pop order
  std::vector<LogMapEntry> entries, stray, merged;
  double radius = 0;
  bool periodic = true;  // angles live on a circle (not at a boundary vertex source)

  State(const Mesh& m, const Tables& t)
      : mesh(m), inner(t.inner), tables(t), value(m.vertexCount(), Value{kInf, 0.0}) {}

  void begin(double r, bool circle) {
    for (int v : touched) value[v].U = kInf;
    touched.clear();
    heap.assign(1, Queued{kInf, -1});
    queued = 0;
    popped.clear();
    deferred.clear();
    entries.clear();
    radius = r;
    periodic = circle;
  }

  void assign(int v, double u, double t) {
    if (value[v].U == kInf) {
      touched.push_back(v);
      // v pops later, after a front's worth of other pops: fetch its ring now, so that the pop does
      // not wait on memory (the order of pops is data-dependent, the hardware cannot guess it). The
      // ring's address needs no load: a prefetch that waits for one (an offset into a table of
      // rings) waits for the same cold memory it is meant to hide.
      const char* const r = reinterpret_cast<const char*>(&tables.ring[v]);
      for (size_t off = 0; off < sizeof(Ring); off += 64) __builtin_prefetch(r + off);
    }
    value[v].U = u;
    value[v].theta = t;
    // Every value is queued, also in the ring just outside R: see run() for what that ring may do.
    // Sifting a hole up, comparing keys only. Equal keys of different vertices do come out in an
    // order that matters (it decides which of two nearly equal updates is kept, kEps): any other
    // queue, or another tie-break, changes results on symmetric meshes and on spot.obj.
    size_t hole = queued++;
    heap.emplace_back(Queued{kInf, -1});
    while (hole > 0) {
      const size_t parent = (hole - 1) / 2;
      if (heap[parent].u <= u) break;
      heap[hole] = heap[parent];
      hole = parent;
    }
    heap[hole] = {u, v};
  }

  // Bottom-up: the hole at the root goes down the smaller children to a leaf without looking at
  // the last entry, then the last entry climbs back above every key it does not exceed. Same heap
  // as the textbook sift-down, but the data-dependent branch per level becomes a select (the choice
  // of child was the solver's most mispredicted branch) and only the short climb tests keys.
  Queued popMin() {
    const Queued top = heap[0];
    const size_t n = --queued;
    const Queued last = heap[n];
    heap[n] = Queued{kInf, -1};
    heap.pop_back();
    size_t hole = 0;
    for (size_t child = 1; child < n; child = 2 * hole + 1) {
      child += heap[child + 1].u < heap[child].u;
      heap[hole] = heap[child];
      hole = child;
    }
    while (hole > 0) {
      const size_t parent = (hole - 1) / 2;
      if (heap[parent].u < last.u) break;
      heap[hole] = heap[parent];
      hole = parent;
    }
    heap[hole] = last;
    return top;
  }

  void seed(int meshVertex, double u, double t) {
    const int v = inner[meshVertex];
    if (u < value[v].U) assign(v, u, wrapTwoPi(t));
  }

  // Updates i from the edge (j, kk) of the counter-clockwise face (j, kk, i), unfolded as e
  // (docs/algorithms.md#log-map).
  [[gnu::always_inline]] void update(int j, int kk, int i, const Unfolded& e) {
    const double Uj = value[j].U, Uk = value[kk].U, Ui = value[i].U;
    // U = 0 would divide in the angle at σ (and the ring of a vertex source is exact already).
    // U_j and U_k are finite: relax() passes a popped vertex and a partner below partnerLimit. No U
    // is NaN (assign() and seed() only accept a smaller value), so one test covers the three zeros.
    if (!(std::min(std::min(Uj, Uk), Ui) > 0)) return;
    double u = kInf, sx = 0, sy = 0, wx = 0, wy = 0;
    bool through = false;
    if (e.d >= kTinyEdge) {
      const double H = heron16(Uj, Uk, e.d);
      if (H >= 0) {
        const double inv2d = e.inv2d;
        sx = ((Uj - Uk) * (Uj + Uk) + e.d * e.d) * inv2d;
        const double sy2 = H * inv2d * inv2d;
        wx = e.ax - sx;
        // |x_i − σ| bounds every candidate from below (a fallback goes via x_j or x_k: triangle
        // inequality), so most updates end here, squared and without a root:
        // |x_i − σ|² = wx² + ay² + σy² + 2 ay |σy| ≥ U_i².
        const double slack = Ui * Ui - (wx * wx + e.ay * e.ay + sy2);
        if (slack <= 0 || 4 * e.ay * e.ay * sy2 >= slack * slack) return;
        sy = -std::sqrt(sy2);
        wy = e.ay - sy;
        // σ→x_i must cross the edge between x_j (left of the ray) and x_k (right of it); otherwise
        // the straight path leaves the face pair and the unfolding underestimates (docs/algorithms.md#log-map).
        through = wy * sx - wx * sy >= 0 && -wx * sy - wy * (e.d - sx) <= 0;
        if (through) u = std::sqrt(wx * wx + wy * wy);
      }
    }
    bool viaJ = true;
    if (!through) {
      const double uj = Uj + e.lj, uk = Uk + e.lk;
      viaJ = uj <= uk;
      u = viaJ ? uj : uk;
    }
    if (!(Ui > u * (1 + kEps))) return;  // U_old / u_new > 1 + eps, written without the division
    double t;
    if (!through) {
      t = theta(viaJ ? j : kk);
    } else {
      const double tj = theta(j), tk = theta(kk);
      if (std::abs(tj - tk) < kEps) {
        t = tj;
      } else {
        // The interpolation waits until Θ_i is read: a quarter of the values are superseded or
        // never read (the ring outside R) by then. Same arithmetic when it runs.
        t = -1.0 - static_cast<double>(deferred.size());
        deferred.push_back({sx, sy, e.d - sx, wx, wy, tj, tk});
      }
    }
    assign(i, u, t);
  }

  // Θ of a vertex with a finite U, interpolating it now if that was deferred.
  double theta(int v) {
    double& stored = value[v].theta;
    if (stored < 0) stored = deferred[static_cast<size_t>(-1.0 - stored)].interpolate(periodic);
    return stored;
  }

  // Face k = (c, n_k, n_k+1) of c's ring, whose slots are `h` (n_k's) and `a` (n_k+1's): updates its
  // apex n_k+1 from (c, n_k) and its head n_k from (n_k+1, c), each only from a partner below
  // `partnerLimit`. Returns false when neither other corner is known yet.
  [[gnu::always_inline]] bool relax(int c, int head, int apex, const RingSlot& h, const RingSlot& a,
                                    double partnerLimit) {
    const double Uhead = value[head].U, Uapex = value[apex].U;
    if (Uhead == kInf && Uapex == kInf) return false;
    // Only from corners known on entry: one first derived just now from the other would only feed back.
    if (Uhead < partnerLimit) update(c, head, apex, unfold(h.d, h.inv2d, a.d, h.dOpp, h.twiceArea));
    if (Uapex < partnerLimit) update(apex, c, head, unfold(a.d, a.inv2d, h.dOpp, h.d, h.twiceArea));
    return true;
  }

  void run() {
    while (queued > 0) {
      const Queued top = popMin();
      const double u = top.u;
      const int c = top.vertex;  // a plain variable: Clang 14 cannot capture a structured binding
      if (u != value[c].U) continue;  // superseded by a later, smaller push
      // Push only if u < R (docs/algorithms.md#log-map): a vertex of the ring just outside does not propagate outwards. It
      // still closes the faces it shares with an inner vertex, though: a vertex inside R next to
      // the rim is often reached straight only through an edge (inner, outer) whose outer end got
      // its value after the inner end had popped, and would otherwise keep a fallback value.
      if (u <= radius) popped.push_back({u, c});
      const double partnerLimit = u < radius ? kInf : radius;
      const Ring& r = tables.ring[c];
      const int m = r.slots, faces = m - r.open;
      const bool inlined = m <= kInlineSlots;
      const std::int32_t* const id = inlined ? r.n : tables.overflowIds.data() + r.overflow;
      const RingSlot* const s = inlined ? r.s : tables.overflowSlots.data() + r.overflow;
      const auto relaxFace = [&](int k) {
        const int kn = k + 1 == m ? 0 : k + 1;
        return relax(c, id[k], id[kn], s[k], s[kn], partnerLimit);
      };
      pending.clear();
      for (int k = 0; k < faces; ++k)
        if (!relaxFace(k)) pending.push_back(k);
      // Faces met before any of their corners was known, visited clockwise so that the values set
      // later in the lap propagate back around c (the lap's start is arbitrary).
      for (auto it = pending.rbegin(); it != pending.rend(); ++it) relaxFace(*it);
    }
  }

  // The entries in the order of their last pop, which is almost the order of distance: pops only
  // go back when a value drops below one popped earlier. Those few are sorted apart and merged in,
  // instead of sorting the whole output (whose comparisons the branch predictor cannot guess).
  const std::vector<LogMapEntry>& collect(int sourceVertex) {
    const auto before = [](const LogMapEntry& a, const LogMapEntry& b) {
      return a.distance < b.distance || (a.distance == b.distance && a.vertex < b.vertex);
    };
    stray.clear();
    for (const auto& [u, v] : popped) {
      if (value[v].U != u) continue;  // popped again later, at its final value
      const LogMapEntry e{tables.ring[v].meshVertex, u, theta(v)};
      if (entries.empty() || !before(e, entries.back())) entries.push_back(e);
      else stray.push_back(e);
    }
    if (!stray.empty()) {
      std::sort(stray.begin(), stray.end(), before);
      merged.resize(entries.size() + stray.size());
      std::merge(entries.begin(), entries.end(), stray.begin(), stray.end(), merged.begin(), before);
      std::swap(entries, merged);
    }
    if (sourceVertex >= 0) entries.insert(entries.begin(), LogMapEntry{sourceVertex, 0.0, 0.0});
    return entries;
  }
};

namespace {

void checkRadius(double radius) {
  // +inf is allowed: the whole connected component.
  if (!(radius > 0)) requirePositive("log map: radius", radius);
}

}  // namespace

LogMap::LogMap(const SurfaceGeometry& geometry)
    : geometry_(geometry), tables_(std::make_shared<const Tables>(geometry)),
      state_(std::make_shared<State>(geometry.mesh(), *tables_)) {}

LogMap::LogMap(const SurfaceGeometry& geometry, std::shared_ptr<const Tables> tables)
    : geometry_(geometry), tables_(std::move(tables)),
      state_(std::make_shared<State>(geometry.mesh(), *tables_)) {}

LogMap LogMap::fork() const { return LogMap(geometry_, tables_); }

const std::vector<LogMapEntry>& LogMap::computeFromVertex(int v, double radius) {
  const Mesh& mesh = geometry_.mesh();
  if (v < 0 || v >= mesh.vertexCount())
    throw InputError("log map: source vertex " + std::to_string(v) + " is out of range (" +
                     std::to_string(mesh.vertexCount()) + " vertices)");
  checkRadius(radius);
  State& s = *state_;
  const bool boundary = mesh.isBoundaryVertex(v);
  // A boundary vertex's angles run over [0, θ(v)] without a seam, so no wrap there.
  s.begin(radius, !boundary);
  s.touched.push_back(s.inner[v]);
  s.value[s.inner[v]] = {0.0, 0.0};
  if (mesh.isIsolated(v)) return s.collect(v);  // no face: only itself
  // The one-ring at edge length and the cone-normalised polar angle of its edge (docs/algorithms.md#log-map).
  int last = -1;
  mesh.forEachOutgoing(v, [&](int h) {
    s.seed(mesh.head(h), geometry_.length(h), geometry_.polarAngle(h));
    last = h;
  });
  if (boundary) {
    // The end of the fan is not the head of an outgoing half-edge: it sits at θ(v), unscaled.
    const int h = Mesh::prev(last);
    s.seed(mesh.tail(h), geometry_.length(h), geometry_.angleSum(v));
  }
  s.run();
  return s.collect(v);
}

const std::vector<LogMapEntry>& LogMap::compute(const SurfacePoint& source, double radius) {
  const Mesh& mesh = geometry_.mesh();
  const int f = source.face;
  if (f < 0 || f >= mesh.faceCount())
    throw InputError("log map: source face " + std::to_string(f) + " is out of range (" +
                     std::to_string(mesh.faceCount()) + " faces)");
  const Vec3& b = source.bary;
  if (!b.allFinite() || b.minCoeff() < -1e-6 || std::abs(b.sum() - 1) > 1e-6) {
    std::ostringstream s;
    s << "log map: source on face " << f << " has barycentric coordinates (" << b.x() << ", " << b.y()
      << ", " << b.z() << "); they must be non-negative and sum to 1";
    throw InputError(s.str());
  }
  checkRadius(radius);
  const int at = source.vertex(mesh);
  if (at >= 0) return computeFromVertex(at, radius);  // the vertex frame, per the contract

  State& s = *state_;
  s.begin(radius, true);
  const Vec3 p = source.position(mesh);
  const Face& tri = mesh.face(f);
  Vec2 x[3];
  // Γ = the face's corners, in the face frame of p: the angles around p sum to exactly 2π, so the
  // result needs no rescale and is directly in the contract's face frame.
  for (int k = 0; k < 3; ++k) {
    x[k] = geometry_.toFaceFrame(f, mesh.position(tri[k]) - p);
    s.seed(tri[k], x[k].norm(), std::atan2(x[k].y(), x[k].x()));
  }
  for (int k = 0; k < 3; ++k) {
    const int h = 3 * f + k, t = mesh.twin(h);
    if (b[(k + 2) % 3] >= kEdgeBary || t < 0) continue;
    // On (or next to) edge k the twin's apex, unfolded across the edge into the face plane, is
    // reached straight through the edge: seed it so that its side of the edge is never guessed.
    const Vec2 tail = x[(k + 1) % 3], dir = (x[k] - tail).normalized();  // twin runs head -> tail
    const Unfolded e = unfold(faceRecord(geometry_, t / 3), t % 3);
    const Vec2 o = tail + e.ax * dir + e.ay * Vec2(-dir.y(), dir.x());
    s.seed(mesh.tail(Mesh::prev(t)), o.norm(), std::atan2(o.y(), o.x()));
  }
  s.run();
  return s.collect(-1);
}

std::vector<LogMapEntry> logMap(const Mesh& mesh, const SurfacePoint& source, double radius) {
  const SurfaceGeometry geometry(mesh);
  LogMap map(geometry);
  return map.compute(source, radius);
}

}  // namespace geoshift

// Log map by discrete geodesic polar coordinates (Melvær–Reimers 2012; ALGORITHMS.md §1).
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
#include <limits>
#include <numbers>
#include <sstream>

#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"

namespace geoshift {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-12;       // relative improvement a new U needs to be accepted (§1 State)
constexpr double kTinyEdge = 1e-11;  // shorter edges cannot place σ (§1 fallbacks: d < 1e-11)
// A face point closer than this (barycentric) to an edge also seeds the twin face's apex: seen from
// a point on the edge its ends are π apart, where the angle wrap rule cannot pick a side (§1).
constexpr double kEdgeBary = 1e-6;

// One face as everything a relaxation needs, in one 64-byte record: the front touches a few
// hundred faces scattered over a large mesh, so a face should cost one cache line.
struct alignas(64) FaceRecord {
  int vertex[3];  // tail of half-edge 3f + k (the fans come from State::fan, not from twins)
  double length[3];  // of half-edge 3f + k
  double twiceArea;
};

// The face of half-edge k (j = tail, k = head, i = apex) unfolded onto x_j = (0,0), x_k = (d,0),
// x_i = (ax, ay), ay > 0 (faces are counter-clockwise, so the apex is on the left).
struct Unfolded {
  double d, inv2d, ax, ay, lj, lk;  // lj = |x_i − x_j|, lk = |x_i − x_k|
};

inline Unfolded unfold(const FaceRecord& r, int k) {
  const double d = r.length[k], lj = r.length[k == 0 ? 2 : k - 1], lk = r.length[k == 2 ? 0 : k + 1];
  const double inv2d = 0.5 / d;
  return {d, inv2d, (lj - lk) * (lj + lk) * inv2d + 0.5 * d, 2 * r.twiceArea * inv2d, lj, lk};
}

// 16 × area² of a triangle with sides x, y, z by the stable Heron product (Kahan): sort a ≥ b ≥ c,
// then (a+(b+c))(c−(a−b))(c+(a−b))(a+(b−c)); negative when the sides violate the triangle
// inequality, which is the first fallback of §1.
inline double heron16(double x, double y, double z) {
  const double a = std::max(std::max(x, y), z);
  const double c = std::min(std::min(x, y), z);
  const double b = std::max(std::min(x, y), std::min(std::max(x, y), z));
  return (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
}

// atan on [0, 1]: Cephes' atan (range split at 0.66 to (x − 1)/(x + 1) + π/4, then a 4/5 rational
// in x²), within 1 ulp of std::atan. glibc's atan2 is correctly rounded and took ~500 instructions
// a call here, the largest single cost of an update; this is ~30 and a division.
inline double atanUnit(double x) {
  constexpr double P0 = -8.750608600031904122785E-1, P1 = -1.615753718733365076637E1,
                   P2 = -7.500855792314704667340E1, P3 = -1.228866684490136173410E2,
                   P4 = -6.485021904942025371773E1;
  constexpr double Q0 = 2.485846490142306297962E1, Q1 = 1.650270098316988542046E2,
                   Q2 = 4.328810604912902668951E2, Q3 = 4.853903996359136964868E2,
                   Q4 = 1.945506571482613964425E2;
  constexpr double kMoreBits = 6.123233995736765886130E-17;  // π/4 − double(π/4), times 2
  double y = 0, extra = 0;
  if (x > 0.66) {
    y = kPi / 4;
    extra = 0.5 * kMoreBits;
    x = (x - 1) / (x + 1);
  }
  const double z = x * x;
  const double p = (((P0 * z + P1) * z + P2) * z + P3) * z + P4;
  const double q = ((((z + Q0) * z + Q1) * z + Q2) * z + Q3) * z + Q4;
  return y + (x * (z * p / q) + x + extra);
}

// Unsigned angle between two plane vectors from (|cross|, dot), as atan2 (accurate near 0 and π
// where acos is not): the smaller of the two over the larger keeps atan's argument in [0, 1].
inline double angleBetween(double ux, double uy, double vx, double vy) {
  const double y = std::abs(ux * vy - uy * vx), x = ux * vx + uy * vy, ax = std::abs(x);
  double a = y <= ax ? atanUnit(y / ax) : kPi / 2 - atanUnit(ax / y);
  if (y == 0 && ax == 0) a = 0;  // atan2(0, ±0): zero vectors (σ at x_j is excluded upstream)
  return x < 0 ? kPi - a : a;
}

struct Queued {
  double u;
  int vertex;
};

inline double wrapTwoPi(double t) {
  if (t < 0) t += kTwoPi;
  if (t >= kTwoPi) t -= kTwoPi;
  return t;
}

}  // namespace

struct LogMap::State {
  const Mesh& mesh;
  std::vector<FaceRecord> faces;
  std::vector<double> U, theta;
  std::vector<int> touched;                     // vertices with a finite U, reset by the next call
  std::vector<Queued> heap;                     // binary min-heap on U with lazy deletion
  std::vector<int> pending;                     // faces around c that had no known corner yet
  std::vector<LogMapEntry> entries;
  // Each vertex's outgoing half-edges in the counter-clockwise order of the run() loop, from
  // halfedge(v): a pop reads them as one array instead of chasing twins face by face, so the
  // (cold) face records around it are fetched in parallel rather than one miss after another.
  std::vector<int> fanStart, fan;
  double radius = 0;
  bool periodic = true;  // angles live on a circle (not at a boundary vertex source)

  explicit State(const SurfaceGeometry& g)
      : mesh(g.mesh()), U(g.mesh().vertexCount(), kInf), theta(g.mesh().vertexCount(), 0.0) {
    const int nf = mesh.faceCount();
    faces.resize(nf);
    for (int f = 0; f < nf; ++f) {
      FaceRecord& r = faces[f];
      for (int k = 0; k < 3; ++k) {
        const int h = 3 * f + k;
        r.vertex[k] = mesh.tail(h);
        r.length[k] = g.length(h);
      }
      // From a corner's sine (atan2-accurate angles), not Heron: needles keep their height.
      r.twiceArea = r.length[0] * r.length[2] * std::sin(g.cornerAngle(3 * f));
    }
    const int nv = mesh.vertexCount();
    fanStart.resize(nv + 1);
    fan.reserve(3 * static_cast<size_t>(nf));
    for (int v = 0; v < nv; ++v) {
      fanStart[v] = static_cast<int>(fan.size());
      const int start = mesh.halfedge(v);
      if (start < 0) continue;  // isolated: never reached
      int h = start;
      do {
        fan.push_back(h);
        h = mesh.ccwOutgoing(h);
      } while (h >= 0 && h != start);
    }
    fanStart[nv] = static_cast<int>(fan.size());
  }

  void begin(double r, bool circle) {
    for (int v : touched) U[v] = kInf;
    touched.clear();
    heap.clear();
    entries.clear();
    radius = r;
    periodic = circle;
  }

  void assign(int v, double u, double t) {
    if (U[v] == kInf) touched.push_back(v);
    U[v] = u;
    theta[v] = t;
    // Every value is queued, also in the ring just outside R: see run() for what that ring may do.
    // Binary heap sifting a hole and comparing keys only (ties need no order: lazy deletion).
    size_t hole = heap.size();
    heap.emplace_back();
    while (hole > 0) {
      const size_t parent = (hole - 1) / 2;
      if (heap[parent].u <= u) break;
      heap[hole] = heap[parent];
      hole = parent;
    }
    heap[hole] = {u, v};
  }

  Queued popMin() {
    const Queued top = heap.front(), last = heap.back();
    heap.pop_back();
    const size_t n = heap.size();
    if (n == 0) return top;
    size_t hole = 0;
    for (;;) {
      size_t child = 2 * hole + 1;
      if (child >= n) break;
      if (child + 1 < n && heap[child + 1].u < heap[child].u) ++child;
      if (last.u <= heap[child].u) break;
      heap[hole] = heap[child];
      hole = child;
    }
    heap[hole] = last;
    return top;
  }

  void seed(int v, double u, double t) {
    if (u < U[v]) assign(v, u, wrapTwoPi(t));
  }

  // Updates i, the apex of half-edge 3f + k, from its edge (j, k) (§1 triangle update).
  [[gnu::always_inline]] void update(const FaceRecord& r, int k) {
    const int j = r.vertex[k], kk = r.vertex[k == 2 ? 0 : k + 1], i = r.vertex[k == 0 ? 2 : k - 1];
    const double Uj = U[j], Uk = U[kk], Ui = U[i];
    // U = 0 would divide in the angle at σ (and the ring of a vertex source is exact already).
    if (Uj == 0 || Uk == 0 || Uj == kInf || Uk == kInf || Ui == 0) return;
    const Unfolded e = unfold(r, k);
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
        // the straight path leaves the face pair and the unfolding underestimates (§1, [V]).
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
      t = viaJ ? theta[j] : theta[kk];
    } else {
      double tj = theta[j], tk = theta[kk];
      if (std::abs(tj - tk) < kEps) {
        t = tj;
      } else {
        // α = ∠(x_j, σ, x_i) / ∠(x_j, σ, x_k) in the unfolded plane.
        const double full = angleBetween(-sx, -sy, e.d - sx, -sy);
        const double alpha = full > 0 ? std::clamp(angleBetween(-sx, -sy, wx, wy) / full, 0.0, 1.0) : 0.0;
        // Wrap rule [V]: the ends of an edge are less than π apart around the source.
        if (periodic && std::abs(tj - tk) > kPi) (tj < tk ? tj : tk) += kTwoPi;
        t = (1 - alpha) * tj + alpha * tk;
        if (t >= kTwoPi) t -= kTwoPi;
      }
    }
    assign(i, u, t);
  }

  // Face 3f + k around c = tail: updates its apex from (c, head) and its head from (apex, c), each
  // only from a partner below `partnerLimit`. Returns false when neither other corner is known yet.
  bool relax(int h, double partnerLimit) {
    const FaceRecord& r = faces[h / 3];
    const int k = h % 3, prev = k == 0 ? 2 : k - 1;
    const double Uhead = U[r.vertex[k == 2 ? 0 : k + 1]], Uapex = U[r.vertex[prev]];
    if (Uhead == kInf && Uapex == kInf) return false;
    // Only from corners known on entry: one first derived just now from the other would only feed back.
    if (Uhead < partnerLimit) update(r, k);
    if (Uapex < partnerLimit) update(r, prev);
    return true;
  }

  void run() {
    while (!heap.empty()) {
      const auto [u, c] = popMin();
      if (u != U[c]) continue;  // superseded by a later, smaller push
      // Push only if u < R (§1): a vertex of the ring just outside does not propagate outwards. It
      // still closes the faces it shares with an inner vertex, though: a vertex inside R next to
      // the rim is often reached straight only through an edge (inner, outer) whose outer end got
      // its value after the inner end had popped, and would otherwise keep a fallback value.
      const double partnerLimit = u < radius ? kInf : radius;
      pending.clear();
      const int* const first = fan.data() + fanStart[c];
      const int* const last = fan.data() + fanStart[c + 1];
      for (const int* it = first; it != last; ++it) __builtin_prefetch(&faces[*it / 3]);
      for (const int* it = first; it != last; ++it)
        if (!relax(*it, partnerLimit)) pending.push_back(*it);
      // Faces met before any of their corners was known, visited clockwise so that the values set
      // later in the lap propagate back around c (the lap's start is arbitrary).
      for (auto it = pending.rbegin(); it != pending.rend(); ++it) relax(*it, partnerLimit);
    }
  }

  const std::vector<LogMapEntry>& collect(int sourceVertex) {
    for (int v : touched)
      if (U[v] <= radius && v != sourceVertex) entries.push_back({v, U[v], theta[v]});
    std::sort(entries.begin(), entries.end(), [](const LogMapEntry& a, const LogMapEntry& b) {
      return a.distance < b.distance || (a.distance == b.distance && a.vertex < b.vertex);
    });
    if (sourceVertex >= 0) entries.insert(entries.begin(), LogMapEntry{sourceVertex, 0.0, 0.0});
    return entries;
  }
};

namespace {

void checkRadius(double radius) {
  // +inf is allowed: the whole connected component.
  if (!(radius > 0)) {
    std::ostringstream s;
    s << "log map: radius must be positive (got " << radius << ")";
    throw InputError(s.str());
  }
}

}  // namespace

LogMap::LogMap(const SurfaceGeometry& geometry)
    : geometry_(geometry), state_(std::make_shared<State>(geometry)) {}

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
  s.touched.push_back(v);
  s.U[v] = 0;
  s.theta[v] = 0;
  if (mesh.isIsolated(v)) return s.collect(v);  // no face: only itself
  // The one-ring at edge length and the cone-normalised polar angle of its edge (§1 vertex source).
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
    const Unfolded e = unfold(s.faces[t / 3], t % 3);
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

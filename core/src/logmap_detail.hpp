#pragma once
// Private to logmap.cpp: the per-vertex ring records and the arithmetic of one DGPC triangle update
// (docs/algorithms.md#log-map), kept apart so that logmap.cpp holds the solver itself.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "geoshift/geodesic.hpp"

namespace geoshift::logmap_detail {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-12;       // relative improvement a new U needs to be accepted (docs/algorithms.md#log-map)
constexpr double kTinyEdge = 1e-11;  // shorter edges cannot place σ (docs/algorithms.md#log-map: the fallbacks)
// A face point closer than this (barycentric) to an edge also seeds the twin face's apex: seen from
// a point on the edge its ends are π apart, where the angle wrap rule cannot pick a side (docs/algorithms.md#log-map).
constexpr double kEdgeBary = 1e-6;

// One face of the mesh, as the seeding across an edge of the source face reads it.
struct FaceRecord {
  int vertex[3];  // tail of half-edge 3f + k
  double length[3];  // of half-edge 3f + k
  double twiceArea;
};

// The face of half-edge k (j = tail, k = head, i = apex) unfolded onto x_j = (0,0), x_k = (d,0),
// x_i = (ax, ay), ay > 0 (faces are counter-clockwise, so the apex is on the left).
struct Unfolded {
  double d, inv2d, ax, ay, lj, lk;  // lj = |x_i − x_j|, lk = |x_i − x_k|
};

inline Unfolded unfold(double d, double inv2d, double lj, double lk, double twiceArea) {
  return {d, inv2d, (lj - lk) * (lj + lk) * inv2d + 0.5 * d, 2 * twiceArea * inv2d, lj, lk};
}

inline FaceRecord faceRecord(const SurfaceGeometry& g, int f) {
  FaceRecord r;
  for (int k = 0; k < 3; ++k) {
    r.vertex[k] = g.mesh().tail(3 * f + k);
    r.length[k] = g.length(3 * f + k);
  }
  // From a corner's sine (atan2-accurate angles), not Heron: needles keep their height.
  r.twiceArea = r.length[0] * r.length[2] * std::sin(g.cornerAngle(3 * f));
  return r;
}

// One neighbour n_k of a vertex c in its ring, and the face (c, n_k, n_k+1) that follows it
// counter-clockwise (absent after the last neighbour of a boundary vertex's open ring).
struct RingSlot {
  double d;          // |n_k − c|
  double inv2d;      // 0.5 / d
  double dOpp;       // |n_k+1 − n_k|, the side of face k opposite c
  double twiceArea;  // of face k
};

// A vertex's ring as a pop reads it, at a fixed stride so that its address needs no load (the
// solver fetches it when the vertex first gets a value, long before it pops). Five cache lines;
// larger rings live in the overflow arrays of LogMap::Tables.
constexpr int kInlineSlots = 8;
struct alignas(64) Ring {
  std::int32_t slots = 0;     // neighbours n_0 .. n_slots-1
  std::int32_t open = 0;      // 1 for a boundary vertex: no face after the last neighbour
  std::int32_t meshVertex = -1;
  std::int32_t overflow = 0;  // first overflow slot when slots > kInlineSlots
  std::int32_t n[kInlineSlots] = {};  // internal vertex ids
  RingSlot s[kInlineSlots] = {};
};
static_assert(sizeof(Ring) == 320);

inline Unfolded unfold(const FaceRecord& r, int k) {
  const double d = r.length[k], lj = r.length[k == 0 ? 2 : k - 1], lk = r.length[k == 2 ? 0 : k + 1];
  return unfold(d, 0.5 / d, lj, lk, r.twiceArea);
}

// 16 × area² of a triangle with sides x, y, z by the stable Heron product (Kahan): sort a ≥ b ≥ c,
// then (a+(b+c))(c−(a−b))(c+(a−b))(a+(b−c)); negative when the sides violate the triangle
// inequality, which is the first fallback (docs/algorithms.md#log-map).
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

// The angle interpolation of one update, kept until the value is read (see LogMap::State::update):
// σ, the x of x_k − σ and x_i − σ in the unfolded face, and the angles at the edge's ends.
struct DeferredAngle {
  double sx, sy, kx, wx, wy, tj, tk;

  double interpolate(bool periodic) const {
    // α = ∠(x_j, σ, x_i) / ∠(x_j, σ, x_k) in the unfolded plane.
    const double full = angleBetween(-sx, -sy, kx, -sy);
    const double alpha = full > 0 ? std::clamp(angleBetween(-sx, -sy, wx, wy) / full, 0.0, 1.0) : 0.0;
    double a = tj, b = tk;
    // Wrap rule [V]: the ends of an edge are less than π apart around the source.
    if (periodic && std::abs(a - b) > kPi) (a < b ? a : b) += kTwoPi;
    const double t = (1 - alpha) * a + alpha * b;
    return t >= kTwoPi ? t - kTwoPi : t;
  }
};

struct Queued {
  double u;
  int vertex;
};

inline double wrapTwoPi(double t) {
  if (t < 0) t += kTwoPi;
  if (t >= kTwoPi) t -= kTwoPi;
  return t;
}

}  // namespace geoshift::logmap_detail

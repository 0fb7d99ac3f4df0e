// Procedural parts for the denoising evaluation (shapes.hpp): thin tubes, thin sheets, thin fins and
// an open sheet with holes. The solids are signed-distance-like fields marched by implicitSurface.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/shapes.hpp"

namespace geoshift::shapes {
namespace {

constexpr double kPi = std::numbers::pi;

void requireDetail(double detail) {
  if (!(detail >= 0.25 && detail <= 8)) {
    throw InputError("shapes: detail must be in [0.25, 8] (got " + std::to_string(detail) + ")");
  }
}

// Distance to an axis-aligned box of half sizes `half` centred at the origin (exact outside).
double boxDistance(const Vec3& p, const Vec3& half) {
  const Vec3 q = p.cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// Rotation of (x, y) about z by angle a.
Vec3 rotateZ(const Vec3& p, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Vec3(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z());
}

}  // namespace

TriangleSoup torusKnot(int p, int q, double tube, double detail) {
  requireDetail(detail);
  if (p < 1 || q < 1 || std::gcd(p, q) != 1) throw InputError("shapes: a torus knot needs coprime p, q >= 1");
  if (!(tube > 0 && tube < 0.9)) throw InputError("shapes: knot tube radius must be in (0, 0.9)");
  auto curve = [&](double t) {
    const double r = 2 + std::cos(q * t);
    return Vec3(r * std::cos(p * t), r * std::sin(p * t), -std::sin(q * t));
  };
  // Length of the curve, then edges about as long along the tube as around it.
  const int sides = std::max(6, static_cast<int>(std::lround(16 * std::sqrt(detail))));
  double length = 0;
  for (int i = 0; i < 4096; ++i) length += (curve(2 * kPi * (i + 1) / 4096) - curve(2 * kPi * i / 4096)).norm();
  const double edge = 2 * kPi * tube / sides;
  const int segments = std::max(16, static_cast<int>(std::lround(length / edge)));
  std::vector<Vec3> point(segments), tangent(segments);
  for (int i = 0; i < segments; ++i) {
    const double t = 2 * kPi * i / segments, dt = 1e-4;
    point[i] = curve(t);
    tangent[i] = (curve(t + dt) - curve(t - dt)).normalized();
  }
  // Rotation-minimising frame by double reflection (Wang et al. 2008), then the angle it has turned
  // by when it comes back to the start spread evenly, so the tube closes without a seam.
  std::vector<Vec3> normal(segments + 1);
  {
    Vec3 a = tangent[0].unitOrthogonal();
    normal[0] = a;
    for (int i = 0; i < segments; ++i) {
      const int j = (i + 1) % segments;
      const Vec3 v1 = point[j] - point[i];
      const double c1 = v1.squaredNorm();
      const Vec3 rL = normal[i] - (2 / c1) * v1.dot(normal[i]) * v1;
      const Vec3 tL = tangent[i] - (2 / c1) * v1.dot(tangent[i]) * v1;
      const Vec3 v2 = tangent[j] - tL;
      const double c2 = v2.squaredNorm();
      normal[i + 1] = (c2 > 0 ? rL - (2 / c2) * v2.dot(rL) * v2 : rL).normalized();
    }
  }
  const Vec3 binormal0 = tangent[0].cross(normal[0]);
  const double closing = std::atan2(normal[segments].dot(binormal0), normal[segments].dot(normal[0]));
  TriangleSoup s;
  for (int i = 0; i < segments; ++i) {
    const Vec3 n = normal[i], b = tangent[i].cross(n);
    for (int j = 0; j < sides; ++j) {
      const double phi = 2 * kPi * j / sides - closing * i / segments;
      s.positions.push_back(point[i] + tube * (std::cos(phi) * n + std::sin(phi) * b));
    }
  }
  for (int i = 0; i < segments; ++i) {
    const int i1 = (i + 1) % segments;
    for (int j = 0; j < sides; ++j) {
      const int j1 = (j + 1) % sides;
      // Along the curve, then around it with the frame's sense: n × b = t, so (t, around) is outward.
      s.faces.push_back({i * sides + j, i1 * sides + j, i1 * sides + j1});
      s.faces.push_back({i * sides + j, i1 * sides + j1, i * sides + j1});
    }
  }
  return s;
}

TriangleSoup turbineBlade(double detail) {
  requireDetail(detail);
  const double halfChord = 0.2, halfThickness = 0.025, halfSpan = 0.5, twist = kPi / 3;
  auto field = [=](const Vec3& x) {
    // Untwist, then the distance to a stadium cross-section extruded along z and cut at both ends.
    const Vec3 p = rotateZ(x, -twist * (x.z() / (2 * halfSpan)));
    const double u = std::max(std::abs(p.x()) - (halfChord - halfThickness), 0.0);
    const double section = std::hypot(u, p.y()) - halfThickness;
    return std::max(section, std::abs(p.z()) - halfSpan);
  };
  const Vec3 hi(0.3, 0.3, 0.55);
  return implicitSurface(field, -hi, hi, 0.0125 / std::sqrt(detail));
}

TriangleSoup thinBowl(double detail) {
  requireDetail(detail);
  auto field = [](const Vec3& p) { return std::max(std::abs(p.norm() - 0.5) - 0.02, p.z() - 0.2); };
  const Vec3 hi(0.56, 0.56, 0.56);
  return implicitSurface(field, -hi, hi, 0.0125 / std::sqrt(detail));
}

TriangleSoup finnedRotor(double detail) {
  requireDetail(detail);
  auto field = [](const Vec3& p) {
    const double hub = std::max(std::hypot(p.x(), p.y()) - 0.25, std::abs(p.z()) - 0.15);
    double d = hub;
    for (int k = 0; k < 6; ++k) {
      const Vec3 q = rotateZ(p, -2 * kPi * k / 6) - Vec3(0.45, 0, 0);
      d = std::min(d, boxDistance(q, Vec3(0.25, 0.018, 0.12)));
    }
    return d;
  };
  const Vec3 hi(0.75, 0.75, 0.2);
  return implicitSurface(field, -hi, hi, 0.01 / std::sqrt(detail));
}

TriangleSoup heatSink(double detail) {
  requireDetail(detail);
  auto field = [](const Vec3& p) {
    double d = boxDistance(p - Vec3(0, 0, -0.2), Vec3(0.5, 0.3, 0.05));
    for (int k = 0; k < 7; ++k) d = std::min(d, boxDistance(p - Vec3(-0.42 + 0.14 * k, 0, 0.05), Vec3(0.015, 0.3, 0.2)));
    return d;
  };
  const Vec3 lo(-0.55, -0.35, -0.3), hi(0.55, 0.35, 0.3);
  return implicitSurface(field, lo, hi, 0.0125 / std::sqrt(detail));
}

TriangleSoup perforatedSheet(int n, unsigned seed) {
  if (n < 8 || n > 2000) throw InputError("shapes: perforated sheet needs n in [8, 2000] (got " + std::to_string(n) + ")");
  const TriangleSoup flat = grid(n, 0.3, seed);
  struct Hole {
    double x, y, r;
  };
  const Hole holes[] = {{0.3, 0.35, 0.12}, {0.7, 0.6, 0.09}, {0.45, 0.78, 0.06}};
  TriangleSoup s;
  std::vector<int> index(flat.positions.size(), -1);
  for (const Face& f : flat.faces) {
    const Vec3 c = (flat.positions[f[0]] + flat.positions[f[1]] + flat.positions[f[2]]) / 3;
    bool cut = false;
    for (const Hole& h : holes) cut = cut || std::hypot(c.x() - h.x, c.y() - h.y) < h.r;
    if (cut) continue;
    Face g;
    for (int k = 0; k < 3; ++k) {
      int& i = index[f[k]];
      if (i < 0) {
        const Vec3& p = flat.positions[f[k]];
        // Bent over a cylinder of radius 0.8 around the y axis.
        const double a = (p.x() - 0.5) / 0.8;
        i = static_cast<int>(s.positions.size());
        s.positions.emplace_back(0.8 * std::sin(a), p.y(), 0.8 * std::cos(a));
      }
      g[k] = i;
    }
    s.faces.push_back(g);
  }
  return s;
}

}  // namespace geoshift::shapes

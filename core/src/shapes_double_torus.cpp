// shapes::doubleTorus: an implicit genus-2 surface (shapes_implicit.cpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/shapes.hpp"

namespace geoshift::shapes {
namespace {

constexpr double kMajor = 1.0, kMinor = 0.4, kOffset = 1.2, kBlend = 0.25;

double torusDistance(const Vec3& p, double cx) {
  const double ring = std::hypot(p.x() - cx, p.y()) - kMajor;
  return std::hypot(ring, p.z()) - kMinor;
}

// Polynomial smooth minimum (Quilez) of the two tori's distances: the tubes merge near x = 0 with a
// rounded saddle instead of a crease, and each torus keeps its hole.
double field(const Vec3& p) {
  const double a = torusDistance(p, -kOffset), b = torusDistance(p, kOffset);
  const double h = std::clamp(0.5 + 0.5 * (b - a) / kBlend, 0.0, 1.0);
  return b + (a - b) * h - kBlend * h * (1.0 - h);
}

}  // namespace

TriangleSoup doubleTorus(int resolution) {
  if (resolution < 16 || resolution > 1024) {
    throw InputError("shapes: double torus resolution must be in [16, 1024] (got " +
                     std::to_string(resolution) + ")");
  }
  const double pad = 0.1;
  const Vec3 lo(-kOffset - kMajor - kMinor - pad, -kMajor - kMinor - pad, -kMinor - pad);
  const Vec3 hi = -lo;
  return implicitSurface(field, lo, hi, (hi.x() - lo.x()) / resolution, 8);
}

}  // namespace geoshift::shapes

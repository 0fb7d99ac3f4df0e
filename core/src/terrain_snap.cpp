// Snapping to the exact-predicate grid, the incircle predicate, and duplicate detection.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geoshift/error.hpp"
#include "terrain_detail.hpp"

namespace geoshift::terrain_detail {

IPoint Snap::operator()(const Vec3& p) const {
  return {static_cast<std::int64_t>(std::llround((p.x() - minX) * scale)),
          static_cast<std::int64_t>(std::llround((p.y() - minY) * scale))};
}

Snap makeSnap(const std::vector<const std::vector<Vec3>*>& sets, const char* what) {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const auto* set : sets)
    for (size_t i = 0; i < set->size(); ++i) {
      const Vec3& p = (*set)[i];
      if (!p.allFinite())
        throw InputError(std::string(what) + " " + std::to_string(i) + " has a NaN or infinite coordinate");
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
  Snap s;
  if (!(x1 >= x0)) return s;  // no points: callers report that themselves
  s.minX = x0;
  s.minY = y0;
  const double extent = std::max(x1 - x0, y1 - y0);
  // Coordinates so far apart that their difference overflows (|x| near 1e308) cannot be put on a
  // grid; an extent so small that the scale overflows puts every point on one grid point (the
  // triangulation then reports them as coincident).
  if (!std::isfinite(extent)) {
    std::ostringstream m;
    m << what << "s span too large a range to triangulate: x from " << x0 << " to " << x1 << ", y from " << y0
      << " to " << y1;
    throw InputError(m.str());
  }
  s.scale = extent > 0 ? double((std::int64_t(1) << kSnapBits) - 1) / extent : 1.0;
  if (!std::isfinite(s.scale)) s.scale = 1.0;
  return s;
}

int inCircle(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d) {
  const std::int64_t adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y;
  const std::int64_t cdx = c.x - d.x, cdy = c.y - d.y;
  // Floating-point filter (Shewchuk's incircle error bound A); the exact sum only near zero.
  const double fa = double(adx) * adx + double(ady) * ady, fb = double(bdx) * bdx + double(bdy) * bdy;
  const double fc = double(cdx) * cdx + double(cdy) * cdy;
  const double bc1 = double(bdx) * cdy, bc2 = double(cdx) * bdy;
  const double ca1 = double(cdx) * ady, ca2 = double(adx) * cdy;
  const double ab1 = double(adx) * bdy, ab2 = double(bdx) * ady;
  const double det = fa * (bc1 - bc2) + fb * (ca1 - ca2) + fc * (ab1 - ab2);
  const double permanent = fa * (std::abs(bc1) + std::abs(bc2)) + fb * (std::abs(ca1) + std::abs(ca2)) +
                           fc * (std::abs(ab1) + std::abs(ab2));
  constexpr double eps = 0x1.0p-53;
  if (std::abs(det) > (10.0 + 96.0 * eps) * eps * permanent) return det > 0 ? 1 : -1;
  __extension__ typedef __int128 I128;  // GCC and Clang (also for wasm32); exact to 2^127
  const I128 la = I128(adx * adx + ady * ady), lb = I128(bdx * bdx + bdy * bdy), lc = I128(cdx * cdx + cdy * cdy);
  const I128 exact = la * I128(bdx * cdy - cdx * bdy) + lb * I128(cdx * ady - adx * cdy) +
                     lc * I128(adx * bdy - bdx * ady);
  return exact > 0 ? 1 : (exact < 0 ? -1 : 0);
}

std::vector<int> firstOfEqual(const std::vector<IPoint>& points, const std::vector<int>& candidates,
                              int pointCount) {
  std::vector<int> keptAs(pointCount, -1);
  struct Key {
    std::int64_t x, y;
    int index;
    bool operator<(const Key& o) const { return x != o.x ? x < o.x : (y != o.y ? y < o.y : index < o.index); }
  };
  std::vector<Key> keys(candidates.size());  // sorted by value, not through the indices: fewer cache misses
  for (size_t i = 0; i < candidates.size(); ++i) keys[i] = {points[candidates[i]].x, points[candidates[i]].y, candidates[i]};
  std::sort(keys.begin(), keys.end());
  for (size_t i = 0; i < keys.size(); ++i) {
    const bool same = i > 0 && keys[i].x == keys[i - 1].x && keys[i].y == keys[i - 1].y;
    keptAs[keys[i].index] = same ? keptAs[keys[i - 1].index] : keys[i].index;
  }
  return keptAs;
}

}  // namespace geoshift::terrain_detail

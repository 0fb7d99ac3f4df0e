#pragma once
// Private to the terrain files: exact predicates on snapped integer coordinates, the sweep-hull
// Delaunay triangulator and point location in its result.
#include <cstdint>
#include <vector>

#include "geoshift/terrain.hpp"

namespace geoshift::terrain_detail {

// Coordinates on a 2^28 grid over a bounding box: orient is exact in int64 (products < 2^58) and
// incircle exact in __int128 (terms < 2^116), which is what makes the flips terminate and the
// result exactly Delaunay even on grids, where nearly every quadruple is cocircular.
constexpr int kSnapBits = 28;

struct IPoint {
  std::int64_t x = 0, y = 0;
  friend bool operator==(const IPoint& a, const IPoint& b) { return a.x == b.x && a.y == b.y; }
};

struct Snap {
  double minX = 0, minY = 0, scale = 1;
  IPoint operator()(const Vec3& p) const;
};

// The grid over the xy bounding box of all of `sets`. Throws InputError naming `what` and the
// index of the first NaN/Inf coordinate.
Snap makeSnap(const std::vector<const std::vector<Vec3>*>& sets, const char* what);

// > 0 when a, b, c turn counter-clockwise, 0 when collinear.
inline std::int64_t orient(const IPoint& a, const IPoint& b, const IPoint& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Z-order (Morton) key of a snapped point clamped to [0, 2^32): sorting by it keeps neighbours
// close in memory.
inline std::uint64_t mortonKey(const IPoint& p) {
  auto spread = [](std::int64_t c) {
    std::uint64_t v = static_cast<std::uint64_t>(c < 0 ? 0 : (c > 0xffffffff ? 0xffffffff : c));
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    return (v | (v << 1)) & 0x5555555555555555ull;
  };
  return spread(p.x) | (spread(p.y) << 1);
}

// > 0 when d is strictly inside the circle through the counter-clockwise a, b, c.
int inCircle(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d);

struct Triangulation {
  std::vector<int> corners;    // 3 per triangle, counter-clockwise
  std::vector<int> halfedges;  // twin of each corner's outgoing edge, -1 on the hull
  std::vector<int> hull;       // counter-clockwise
  int triangleCount() const { return static_cast<int>(corners.size() / 3); }
};

// Delaunay triangulation of the points `use` (distinct positions, indices into `points`).
// Throws InputError when fewer than three are given or all are collinear.
Triangulation triangulate(const std::vector<IPoint>& points, const std::vector<int>& use,
                          InsertionOrder order, const Progress& progress);

// Keeps the first of every run of equal points: keptAs[i] = i or the earlier point's index.
std::vector<int> firstOfEqual(const std::vector<IPoint>& points, const std::vector<int>& candidates,
                              int pointCount);

// Linear interpolation of z over a triangulation by walking from the last triangle found. The walk
// uses the snapped points; the weights come from the unsnapped ones (`original`, also giving z).
class SurfaceLocator {
 public:
  SurfaceLocator(const Triangulation& t, const std::vector<IPoint>& points, const std::vector<Vec3>& original);
  // z of the surface at q (snapped) / qx, qy (unsnapped): barycentric inside; outside, along the
  // nearest hull edge.
  double heightAt(const IPoint& q, double qx, double qy);

 private:
  double outside(double qx, double qy, int hullEdge);
  const Triangulation& t_;
  const std::vector<IPoint>& p_;
  const std::vector<Vec3>& o_;
  std::vector<int> hullIndex_;  // point -> position in t_.hull, -1 when not on the hull
  int last_ = 0;
  std::uint32_t rng_ = 0x9e3779b9u;
};

}  // namespace geoshift::terrain_detail

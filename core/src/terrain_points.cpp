// Point-cloud terrains: the TIN of a point set, and heights above the TIN of its ground class.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geoshift/error.hpp"
#include "terrain_detail.hpp"

namespace geoshift::terrain_detail {

SurfaceLocator::SurfaceLocator(const Triangulation& t, const std::vector<IPoint>& points,
                               const std::vector<Vec3>& original)
    : t_(t), p_(points), o_(original), hullIndex_(points.size(), -1) {
  for (size_t k = 0; k < t.hull.size(); ++k) hullIndex_[t.hull[k]] = static_cast<int>(k);
}

double SurfaceLocator::heightAt(const IPoint& q, double qx, double qy) {
  const auto& c = t_.corners;
  int t = last_;
  for (;;) {
    // Visibility walk; a random first edge per triangle rules out cycles.
    rng_ = rng_ * 1664525u + 1013904223u;
    const int k0 = static_cast<int>((rng_ >> 16) % 3);
    int next = -1;
    for (int j = 0; j < 3; ++j) {
      const int h = 3 * t + (k0 + j) % 3;
      const int a = c[h], b = c[3 * t + (h + 1) % 3];
      if (orient(p_[a], p_[b], q) < 0) {
        if (t_.halfedges[h] < 0) {
          last_ = t;
          return outside(qx, qy, h);
        }
        next = t_.halfedges[h] / 3;
        break;
      }
    }
    if (next < 0) break;
    t = next;
  }
  last_ = t;
  const int a = c[3 * t], b = c[3 * t + 1], d = c[3 * t + 2];
  for (int v : {a, b, d})
    if (p_[v] == q) return o_[v].z();
  // Barycentric weights from the unsnapped coordinates (snapping would cost ~1e-8 of the extent);
  // a point the snapped walk put in this triangle may be a rounding step outside it, so the
  // weights are clamped before normalising.
  auto area = [&](int i, int j) {
    return (o_[j].x() - o_[i].x()) * (qy - o_[i].y()) - (o_[j].y() - o_[i].y()) * (qx - o_[i].x());
  };
  const double wa = std::max(0.0, area(b, d)), wb = std::max(0.0, area(d, a)), wd = std::max(0.0, area(a, b));
  const double sum = wa + wb + wd;
  if (!(sum > 0)) return o_[a].z();
  return (wa * o_[a].z() + wb * o_[b].z() + wd * o_[d].z()) / sum;
}

// Outside the hull: the nearest hull edge is found by descending along the hull from the edge the
// walk left through; z is interpolated along that edge (clamped to its ends).
double SurfaceLocator::outside(double qx, double qy, int hullEdge) {
  const auto& hull = t_.hull;
  const int m = static_cast<int>(hull.size());
  auto edgeDist = [&](int k, double* tOut) {
    const Vec3& a = o_[hull[k]];
    const Vec3& b = o_[hull[(k + 1) % m]];
    const double ex = b.x() - a.x(), ey = b.y() - a.y();
    const double rx = qx - a.x(), ry = qy - a.y();
    const double len2 = ex * ex + ey * ey;
    const double t = len2 > 0 ? std::clamp((rx * ex + ry * ey) / len2, 0.0, 1.0) : 0.0;
    if (tOut) *tOut = t;
    const double dx = rx - t * ex, dy = ry - t * ey;
    return dx * dx + dy * dy;
  };
  int k = hullIndex_[t_.corners[hullEdge]];
  double d = edgeDist(k, nullptr);
  for (int dir : {1, -1}) {
    for (int step = 0; step < m; ++step) {
      const int kn = ((k + dir) % m + m) % m;
      const double dn = edgeDist(kn, nullptr);
      if (!(dn < d)) break;
      k = kn, d = dn;
    }
  }
  double t = 0;
  edgeDist(k, &t);
  return (1 - t) * o_[hull[k]].z() + t * o_[hull[(k + 1) % m]].z();
}

}  // namespace geoshift::terrain_detail

namespace geoshift {
namespace {

using namespace terrain_detail;

// Spatially coherent order so that each walk starts near its point.
std::vector<int> mortonOrder(const std::vector<IPoint>& q) {
  std::vector<std::pair<std::uint64_t, int>> keyed(q.size());
  for (size_t i = 0; i < q.size(); ++i) keyed[i] = {mortonKey(q[i]), static_cast<int>(i)};
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order(q.size());
  for (size_t i = 0; i < q.size(); ++i) order[i] = keyed[i].second;
  return order;
}

// Heights of `queries` above the TIN of `ground`, both already snapped on one grid.
std::vector<double> heightsOnGrid(const std::vector<IPoint>& groundIp, const std::vector<Vec3>& ground,
                                  const std::vector<IPoint>& queryIp, const std::vector<Vec3>& query,
                                  const Progress& progress) {
  std::vector<int> all(groundIp.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<int> keptAs = firstOfEqual(groundIp, all, static_cast<int>(groundIp.size()));
  std::vector<int> use;
  for (size_t i = 0; i < keptAs.size(); ++i)
    if (keptAs[i] == static_cast<int>(i)) use.push_back(static_cast<int>(i));
  const Triangulation tin = triangulate(groundIp, use, InsertionOrder::Sweep, progress);
  SurfaceLocator locator(tin, groundIp, ground);
  std::vector<double> h(queryIp.size());
  const std::vector<int> order = mortonOrder(queryIp);
  for (size_t k = 0; k < order.size(); ++k) {
    if ((k & 0xffff) == 0) progress.step(double(k) / order.size(), "height above ground");
    const int i = order[k];
    h[i] = query[i].z() - locator.heightAt(queryIp[i], query[i].x(), query[i].y());
  }
  return h;
}

}  // namespace

std::vector<double> heightAboveGround(const std::vector<Vec3>& ground, const std::vector<Vec3>& points,
                                      const Progress& progress) {
  const Snap snap = makeSnap({&ground}, "ground point");
  makeSnap({&points}, "point");  // only for its NaN/Inf check
  std::vector<IPoint> gi(ground.size()), qi(points.size());
  for (size_t i = 0; i < ground.size(); ++i) gi[i] = snap(ground[i]);
  // Far-away queries would overflow the exact predicates; clamp them into a margin around the
  // ground's box (beyond it the answer comes from the nearest hull edge anyway).
  constexpr double lim = double(std::int64_t(1) << (kSnapBits + 1));
  for (size_t i = 0; i < points.size(); ++i) {
    const double x = std::clamp((points[i].x() - snap.minX) * snap.scale, -lim, lim);
    const double y = std::clamp((points[i].y() - snap.minY) * snap.scale, -lim, lim);
    qi[i] = {std::llround(x), std::llround(y)};
  }
  return heightsOnGrid(gi, ground, qi, points, progress);
}

TerrainMesh pointTerrain(const TerrainPoints& points, const PointTerrainOptions& options,
                         const Progress& progress) {
  const size_t n = points.positions.size();
  if (!points.classes.empty() && points.classes.size() != n)
    throw InputError("point terrain: " + std::to_string(points.classes.size()) + " classes for " +
                     std::to_string(n) + " points");
  if (!points.colors.empty() && points.colors.size() != n)
    throw InputError("point terrain: " + std::to_string(points.colors.size()) + " colors for " +
                     std::to_string(n) + " points");
  const Snap snap = makeSnap({&points.positions}, "point");
  std::vector<IPoint> ip(n);
  for (size_t i = 0; i < n; ++i) ip[i] = snap(points.positions[i]);

  TerrainMesh out;
  out.report.pointsRead = static_cast<std::int64_t>(n);
  std::vector<int> groundIdx;
  if (!points.classes.empty())
    for (size_t i = 0; i < n; ++i)
      if (points.classes[i] == options.groundClass) groundIdx.push_back(static_cast<int>(i));
  out.report.groundPoints = static_cast<std::int64_t>(groundIdx.size());

  std::vector<int> selected;
  if (options.groundOnly) {
    if (points.classes.empty()) throw InputError("ground only: the points have no classification");
    selected = groundIdx;
  } else {
    selected.resize(n);
    std::iota(selected.begin(), selected.end(), 0);
  }
  const std::string what = options.groundOnly ? "ground (class " + std::to_string(options.groundClass) + ") points"
                                              : "points";
  const std::vector<int> keptAs = firstOfEqual(ip, selected, static_cast<int>(n));
  std::vector<int> use;
  for (int i : selected)
    if (keptAs[i] == i) use.push_back(i);
  out.report.duplicatesDropped = static_cast<std::int64_t>(selected.size() - use.size());
  Triangulation t;
  try {
    t = triangulate(ip, use, InsertionOrder::Sweep, progress);
  } catch (const InputError& e) {
    throw InputError("cannot triangulate the " + std::to_string(use.size()) + " " + what + ": " + e.what());
  }

  // Vertices in input order of the kept points.
  std::vector<int> vertexOf(n, -1);
  std::vector<int> sortedUse = use;
  std::sort(sortedUse.begin(), sortedUse.end());
  for (size_t k = 0; k < sortedUse.size(); ++k) vertexOf[sortedUse[k]] = static_cast<int>(k);
  out.positions.resize(sortedUse.size());
  for (size_t k = 0; k < sortedUse.size(); ++k) out.positions[k] = points.positions[sortedUse[k]];
  out.faces.resize(t.triangleCount());
  for (int f = 0; f < t.triangleCount(); ++f)
    out.faces[f] = {vertexOf[t.corners[3 * f]], vertexOf[t.corners[3 * f + 1]], vertexOf[t.corners[3 * f + 2]]};
  out.report.pointsUsed = static_cast<std::int64_t>(sortedUse.size());
  if (out.report.duplicatesDropped > 0)
    out.report.notes.push_back(std::to_string(out.report.duplicatesDropped) +
                               " points share their xy with an earlier point and were left out (first kept)");

  const int nv = static_cast<int>(sortedUse.size());
  out.attributes = AttributeSet(nv);
  std::vector<double> hag(nv);
  bool fromTin = groundIdx.size() >= 3;
  if (fromTin) {
    std::vector<IPoint> gi, qi(nv);
    std::vector<Vec3> g;
    for (int i : groundIdx) gi.push_back(ip[i]), g.push_back(points.positions[i]);
    for (int k = 0; k < nv; ++k) qi[k] = ip[sortedUse[k]];
    try {
      hag = heightsOnGrid(gi, g, qi, out.positions, progress);
    } catch (const InputError&) {
      fromTin = false;  // collinear ground
    }
  }
  if (fromTin) {
    out.report.notes.push_back("height above ground: against the TIN of the " + std::to_string(groundIdx.size()) +
                               " class-" + std::to_string(options.groundClass) + " points");
  } else {
    double zmin = std::numeric_limits<double>::infinity();
    for (const Vec3& p : out.positions) zmin = std::min(zmin, p.z());
    for (int k = 0; k < nv; ++k) hag[k] = out.positions[k].z() - zmin;
    out.report.notes.push_back("height above ground: no usable ground class " + std::to_string(options.groundClass) +
                               " (" + std::to_string(groundIdx.size()) + " points), so z minus the minimum z");
  }
  out.attributes.set("_HEIGHT_ABOVE_GROUND", 1, AttributeKind::Euclidean, std::move(hag));
  if (!points.classes.empty()) {
    std::vector<double> cls(nv);
    for (int k = 0; k < nv; ++k) cls[k] = points.classes[sortedUse[k]];
    out.attributes.set("_CLASS", 1, AttributeKind::Euclidean, std::move(cls));
  }
  if (!points.colors.empty()) {
    std::vector<double> rgb(3 * static_cast<size_t>(nv));
    for (int k = 0; k < nv; ++k)
      for (int c = 0; c < 3; ++c) rgb[3 * static_cast<size_t>(k) + c] = points.colors[sortedUse[k]][c];
    out.attributes.set("COLOR_0", 3, AttributeKind::Euclidean, std::move(rgb));
  }
  return out;
}

}  // namespace geoshift

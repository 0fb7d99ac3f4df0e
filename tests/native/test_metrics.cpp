// Error metrics (docs/algorithms.md#noise-and-error-metrics): per-vertex RMS, MeshLab-style point-to-surface, normal angles.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

// The reference loops over all faces with a formula independent of Ericson's region tests: project
// onto the plane; if the projection falls outside the triangle, take the closest of its three edges.
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

double triangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a).normalized();
  const Vec3 q = p - (p - a).dot(n) * n;
  // q inside iff it is on the inner side of all three edges.
  const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                      (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return std::abs((p - a).dot(n));
  return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
}

double bruteForce(const Vec3& p, const Mesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (const Face& f : m.faces()) {
    best = std::min(best, triangleDistance(p, m.position(f[0]), m.position(f[1]), m.position(f[2])));
  }
  return best;
}

}  // namespace

TEST_CASE("per-vertex RMS", "[metrics][rms]") {
  CHECK(perVertexRms({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(3, 4, 0), Vec3(1, 1, 1)}) ==
        Approx(std::sqrt(25.0 / 2)));
  CHECK_THROWS_AS(perVertexRms({Vec3::Zero()}, {}), InputError);
}

TEST_CASE("a mesh against itself is at distance 0", "[metrics][hausdorff]") {
  const Mesh m = build(shapes::torus(40, 20));
  const DistanceStats s = pointToSurface(m.positions(), m);
  CHECK(s.samples == m.vertexCount());
  CHECK(s.dropped == 0);
  CHECK(s.max < 1e-12);
  CHECK(s.rms < 1e-12);
  CHECK(s.diagonal == Approx(boundingBox(m.positions()).diagonal().norm()));
}

TEST_CASE("a plane offset by δ gives RMS δ", "[metrics][hausdorff]") {
  const Mesh target = build(shapes::grid(30, 0.3));
  const double delta = 0.0123;
  std::vector<Vec3> samples = target.positions();
  for (Vec3& p : samples) p.z() += delta;
  const DistanceStats s = pointToSurface(samples, target);
  CHECK(s.samples == target.vertexCount());
  CHECK(s.rms == Approx(delta).epsilon(1e-12));
  CHECK(s.min == Approx(delta).epsilon(1e-12));
  CHECK(s.max == Approx(delta).epsilon(1e-12));
  CHECK(s.mean == Approx(delta).epsilon(1e-12));
}

TEST_CASE("grid search equals brute force over all faces", "[metrics][hausdorff]") {
  // A bumpy open surface and points all around it, inside and far outside its bounding box.
  TriangleSoup soup = shapes::grid(12, 0.3, 5);
  for (Vec3& p : soup.positions) p.z() = 0.2 * std::sin(7 * p.x()) * std::cos(5 * p.y());
  const Mesh target = build(soup);
  std::mt19937_64 rng(77);
  auto u = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  std::vector<Vec3> samples;
  for (int i = 0; i < 2000; ++i) samples.emplace_back(3 * u() - 1, 3 * u() - 1, 2 * u() - 1);
  for (const Vec3& p : target.positions()) samples.push_back(p + Vec3(0, 0, 1e-3 * (u() - 0.5)));
  PointToSurfaceOptions options;
  options.maxDistance = 1e9;  // keep everything
  const DistanceStats s = pointToSurface(samples, target, options);
  REQUIRE(s.samples == static_cast<int>(samples.size()));
  double max = 0, sum2 = 0;
  double min = std::numeric_limits<double>::infinity();
  for (const Vec3& p : samples) {
    const double d = bruteForce(p, target);
    max = std::max(max, d);
    min = std::min(min, d);
    sum2 += d * d;
  }
  CHECK(s.max == Approx(max).epsilon(1e-12));
  CHECK(s.min == Approx(min).epsilon(1e-9));
  CHECK(s.rms == Approx(std::sqrt(sum2 / samples.size())).epsilon(1e-12));
  // And each sample one by one.
  for (size_t i = 0; i < samples.size(); i += 37) {
    const DistanceStats one = pointToSurface({samples[i]}, target, options);
    CHECK(one.max == Approx(bruteForce(samples[i], target)).epsilon(1e-12).margin(1e-15));
  }
}

TEST_CASE("samples at or beyond maxDistance are dropped", "[metrics][hausdorff]") {
  const Mesh target = build(shapes::grid(5));
  const std::vector<Vec3> samples = {Vec3(0.5, 0.5, 0.1), Vec3(0.5, 0.5, 0.3), Vec3(0.5, 0.5, 0.5),
                                     Vec3(0.2, 0.2, -0.29)};
  PointToSurfaceOptions options;
  options.maxDistance = 0.3;
  const DistanceStats s = pointToSurface(samples, target, options);
  CHECK(s.samples == 2);  // 0.1 and 0.29; 0.3 is "at" the limit
  CHECK(s.dropped == 2);
  CHECK(s.max == Approx(0.29));
  CHECK(s.min == Approx(0.1));
  // Default: half the target's diagonal (√2 / 2 for the unit square).
  const DistanceStats d = pointToSurface({Vec3(0.5, 0.5, 0.7), Vec3(0.5, 0.5, 0.71)}, target);
  CHECK(d.samples == 1);
  CHECK(d.dropped == 1);
}

// Speed is measured in bench/bench_geometry.cpp, not here; this checks the grid search on a large
// case against the analytic answer: samples at radii 1.01, 0.9999 and 0.989901 of a unit icosphere
// lie above or below its vertices, so at most 0.010099 and at least 1e-4 minus the facet sag
// (< 6e-5 at this resolution) from the surface.
TEST_CASE("point-to-surface on 100k samples against 80k faces", "[metrics]") {
  const Mesh target = build(shapes::icosphere(6));  // 81920 faces
  Mesh sampled = build(shapes::icosphere(6, 1.01));
  std::vector<Vec3> samples = sampled.positions();
  for (size_t i = 0; samples.size() < 100000; ++i) samples.push_back(0.99 * samples[i]);
  const DistanceStats s = pointToSurface(samples, target);
  CHECK(s.samples == 100000);
  CHECK(s.min > 1e-4 - 6e-5);
  CHECK(s.min <= 1e-4 + 1e-12);
  CHECK(s.max <= 1 - 0.99 * 0.99 * 1.01 + 1e-12);
  CHECK(s.max > 0.0100);
}

TEST_CASE("mean normal angle error", "[metrics][normals]") {
  const Mesh m = build(shapes::icosphere(2));
  CHECK(meanNormalAngleError(m, m) == 0.0);

  // Tetrahedron with one face flipped: that face is off by 180°, the other three by 0. Its faces
  // share no vertex, so the mesh has no neighbour to turn the flipped face back by.
  TriangleSoup tet = shapes::unwelded(shapes::tetrahedron());
  const Mesh reference(tet.positions, tet.faces);
  std::swap(tet.faces[0][1], tet.faces[0][2]);
  const Mesh flipped(tet.positions, tet.faces);
  REQUIRE(flipped.faceCount() == 4);
  CHECK(meanNormalAngleError(flipped, reference) == Approx(45.0).epsilon(1e-12));

  // One triangle tilted by exactly 30° about the x axis.
  const double a = M_PI / 6;
  const Mesh flat({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}});
  const Mesh tilted({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::cos(a), std::sin(a))}, {{0, 1, 2}});
  CHECK(meanNormalAngleError(tilted, flat) == Approx(30.0).epsilon(1e-12));
  CHECK_THROWS_AS(meanNormalAngleError(flat, m), InputError);
}

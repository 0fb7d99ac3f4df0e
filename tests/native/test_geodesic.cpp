// Log and exp maps together: exp_p(log_p(q)) = q, the round trip the mean shift relies on (every
// iteration averages log vectors and walks the exp map), in the one frame convention both share.
#include <catch2/catch.hpp>

#include <cmath>

#include "geoshift/geodesic.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

// Worst |exp_p(log_p(v)) - v| over the vertices v within `radius` of p, and how many were checked.
std::pair<double, int> roundTrip(const SurfaceGeometry& g, LogMap& log, const SurfacePoint& p, double radius) {
  double worst = 0;
  int count = 0;
  for (const LogMapEntry& e : log.compute(p, radius)) {
    if (e.distance == 0) continue;
    const ExpMapResult r = expMap(g, p, e.coords());
    if (r.hitBoundary) continue;
    worst = std::max(worst, (r.end.position(g.mesh()) - g.mesh().position(e.vertex)).norm());
    ++count;
  }
  return {worst, count};
}

}  // namespace

TEST_CASE("exp(log(q)) = q on a jittered plane, from vertices and face points", "[geodesic]") {
  const Mesh mesh = buildMesh(shapes::grid(41, 0.2)).mesh;
  const SurfaceGeometry g(mesh);
  LogMap log(g);
  const double R = 5 * g.averageEdgeLength();
  for (int v : {20 * 41 + 20, 15 * 41 + 22, 25 * 41 + 17}) {
    const auto [worst, count] = roundTrip(g, log, SurfacePoint::atVertex(mesh, v), R);
    REQUIRE(count > 40);
    REQUIRE(worst < 1e-9);
  }
  for (int f : {1400, 1601, 1777}) {
    const auto [worst, count] = roundTrip(g, log, SurfacePoint::inFace(mesh, f, Vec3(0.25, 0.6, 0.15)), R);
    REQUIRE(count > 40);
    REQUIRE(worst < 1e-9);
  }
  // A point on an edge uses the face frame of its face; both sides of the edge round-trip.
  const int h = 3 * 1600 + 1;
  REQUIRE(mesh.twin(h) >= 0);
  const auto [worst, count] = roundTrip(g, log, SurfacePoint::onEdge(mesh, h, 0.4), R);
  REQUIRE(count > 40);
  REQUIRE(worst < 1e-9);
}

TEST_CASE("exp(log(q)) = q on an intrinsically flat prism cylinder", "[geodesic]") {
  const Mesh mesh = buildMesh(shapes::cylinder(48, 60, 1.0, 4.0)).mesh;
  const SurfaceGeometry g(mesh);
  LogMap log(g);
  // Radius well below half the perimeter, so no path wraps around.
  const double R = 1.0;
  const auto [worst, count] = roundTrip(g, log, SurfacePoint::atVertex(mesh, 30 * 48 + 5), R);
  REQUIRE(count > 100);
  REQUIRE(worst < 1e-8);
}

TEST_CASE("exp(log(q)) ~ q on a sphere inside the injectivity radius, better with refinement", "[geodesic]") {
  double previous = 1e9;
  for (int level : {3, 4, 5}) {
    const Mesh mesh = buildMesh(shapes::icosphere(level)).mesh;
    const SurfaceGeometry g(mesh);
    LogMap log(g);
    const double R = 0.5;  // radius 1: far inside the injectivity radius π
    double worst = 0;
    for (int v : {0, 7, mesh.vertexCount() / 2}) {
      const auto [w, count] = roundTrip(g, log, SurfacePoint::atVertex(mesh, v), R);
      REQUIRE(count > 10);
      worst = std::max(worst, w);
    }
    const auto [wf, countf] = roundTrip(g, log, SurfacePoint::inFace(mesh, 11, Vec3(0.3, 0.3, 0.4)), R);
    REQUIRE(countf > 10);
    worst = std::max(worst, wf);
    INFO("level " << level << ": worst round-trip error " << worst);
    REQUIRE(worst < 0.05 * R);
    REQUIRE(worst < previous);
    previous = worst;
  }
}

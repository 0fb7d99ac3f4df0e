// Discrete curvatures (docs/algorithms.md#curvature) against analytic answers (docs/testing.md#what-tests-assert).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geoshift/curvature.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;
using std::numbers::pi;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

double totalCurvature(const Curvatures& c) {
  double s = 0;
  for (size_t v = 0; v < c.area.size(); ++v) s += c.gaussian[v] * c.area[v];
  return s;
}

}  // namespace

TEST_CASE("sphere: H = 1/R, K = 1/R², ABS = 2/R at every vertex", "[curvature][sphere]") {
  const double R = 2.0;
  const Mesh m = build(shapes::icosphere(5, R));
  REQUIRE(m.vertexCount() == 10242);
  const Curvatures c = curvatures(m);
  double worstH = 0, worstK = 0, worstAbs = 0, meanH = 0;
  for (int v = 0; v < m.vertexCount(); ++v) {
    worstH = std::max(worstH, std::abs(c.mean[v] * R - 1));
    worstK = std::max(worstK, std::abs(c.gaussian[v] * R * R - 1));
    worstAbs = std::max(worstAbs, std::abs(c.absolute(v) * R / 2 - 1));
    meanH += c.mean[v] / m.vertexCount();
  }
  INFO("worst relative error: H " << worstH << ", K " << worstK << ", ABS " << worstAbs);
  CHECK(meanH * R == Approx(1.0).epsilon(1e-5));
  // Measured at level 5: H 2.2e-6, K 3.6e-4 (the brief asked for 2%; far tighter holds).
  CHECK(worstH < 1e-4);
  CHECK(worstK < 2e-3);
  CHECK(worstAbs < 1e-4);
  // Total Gaussian curvature is a topological invariant of the discrete mesh.
  CHECK(totalCurvature(c) == Approx(4 * pi).epsilon(1e-12));
}

TEST_CASE("Gauss–Bonnet: Σ K A = 2π χ", "[curvature][gauss-bonnet]") {
  CHECK(std::abs(totalCurvature(curvatures(build(shapes::tetrahedron()))) - 4 * pi) < 1e-9);
  CHECK(std::abs(totalCurvature(curvatures(build(shapes::cube()))) - 4 * pi) < 1e-9);
  CHECK(std::abs(totalCurvature(curvatures(build(shapes::icosphere(2, 0.3)))) - 4 * pi) < 1e-9);
  CHECK(std::abs(totalCurvature(curvatures(build(shapes::torus(48, 24))))) < 1e-9);
}

TEST_CASE("cylinder: H = 1/(2R), K = 0 at interior vertices", "[curvature][cylinder]") {
  const double R = 1.5;
  const Mesh m = build(shapes::cylinder(256, 12, R, 2.0));
  const Curvatures c = curvatures(m);
  int interior = 0;
  for (int v = 0; v < m.vertexCount(); ++v) {
    if (m.isBoundaryVertex(v)) continue;
    ++interior;
    CHECK(c.mean[v] * 2 * R == Approx(1.0).epsilon(1e-9));  // exact for the prism (measured 6e-13)
    CHECK(std::abs(c.gaussian[v]) < 1e-9);  // a prism is intrinsically flat
    CHECK(c.absolute(v) * R == Approx(1.0).epsilon(1e-9));
  }
  CHECK(interior == 256 * 10);
}

TEST_CASE("flat jittered grid: H = K = 0, including the border", "[curvature][plane]") {
  const Mesh m = build(shapes::grid(21, 0.3, 3));
  const Curvatures c = curvatures(m);
  const auto corner = [&](int v) {
    const Vec3& p = m.position(v);
    return (p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1);
  };
  for (int v = 0; v < m.vertexCount(); ++v) {
    INFO("vertex " << v << (m.isBoundaryVertex(v) ? " (boundary)" : ""));
    CHECK(std::abs(c.mean[v]) < 1e-9);
    if (corner(v)) {
      // MeshLab's correction 2π − Σθ − β gives 2π − 2β at a convex corner (β = π/2 here).
      CHECK(c.gaussian[v] * c.area[v] == Approx(pi).epsilon(1e-12));
    } else {
      CHECK(std::abs(c.gaussian[v]) < 1e-9);
    }
  }
}

TEST_CASE("saddle z = x² − y² at the origin: H = 0, K = −4, ABS = 4", "[curvature][saddle]") {
  const int n = 41;  // odd: the origin is a vertex
  TriangleSoup soup = shapes::grid(n);
  const double L = 0.1;
  int origin = -1;
  for (size_t i = 0; i < soup.positions.size(); ++i) {
    Vec3& p = soup.positions[i];
    p.x() = (p.x() - 0.5) * L;
    p.y() = (p.y() - 0.5) * L;
    p.z() = p.x() * p.x() - p.y() * p.y();
    if (p.head<2>().norm() < 1e-12) origin = static_cast<int>(i);
  }
  REQUIRE(origin >= 0);
  const MeshBuild b = buildMesh(soup);
  const int v = b.vertexOf[origin];
  const Curvatures c = curvatures(b.mesh);
  CHECK(std::abs(c.mean[v]) < 0.02);
  CHECK(c.gaussian[v] == Approx(-4.0).epsilon(0.02));
  CHECK(c.absolute(v) == Approx(4.0).epsilon(0.02));
  CHECK(c.rms(v) == Approx(std::sqrt(8.0)).epsilon(0.02));  // sqrt(k1² + k2²) = sqrt(2² + 2²)
}

TEST_CASE("sign of H follows the outward normal", "[curvature][sign]") {
  TriangleSoup inside = shapes::icosphere(3);
  for (Face& f : inside.faces) std::swap(f[1], f[2]);  // normals now point inward
  const Curvatures c = curvatures(build(inside));
  for (double h : c.mean) CHECK(h < 0);
}

TEST_CASE("derived quantities and the colour map", "[curvature][derived]") {
  Curvatures c;
  c.mean = {1.0, 0.0, -2.0};
  c.gaussian = {1.0, -4.0, 3.0};
  c.area = {1, 1, 1};
  CHECK(c.absolute(0) == Approx(2.0));  // k1 = k2 = 1
  CHECK(c.absolute(1) == Approx(4.0));  // k = ±2
  CHECK(c.get(CurvatureKind::Absolute)[2] == Approx(4.0));
  CHECK(c.rms(1) == Approx(std::sqrt(8.0)));
  CHECK(c.get(CurvatureKind::Mean) == c.mean);

  std::vector<double> values(101);
  for (int i = 0; i <= 100; ++i) values[i] = i - 50.0;
  values[0] = -1e9;  // a spike must not change the other colours (percentile clamp)
  const std::vector<double> rgb = colorMap(values);
  REQUIRE(rgb.size() == 3 * values.size());
  for (double x : rgb) CHECK((x >= 0 && x <= 1));
  // Diverging map: zero is white, and everything beyond the 10% percentile is clamped.
  CHECK(rgb[3 * 50] == Approx(1.0));
  CHECK(rgb[3 * 50 + 2] == Approx(1.0));
  for (int j = 0; j < 3; ++j) CHECK(rgb[j] == Approx(rgb[3 * 5 + j]));
  std::vector<double> spiked = values;
  spiked[0] = -60;
  const std::vector<double> rgb2 = colorMap(spiked);
  for (int i = 3; i < 303; ++i) CHECK(rgb2[i] == Approx(rgb[i]));
}

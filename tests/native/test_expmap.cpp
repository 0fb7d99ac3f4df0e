// Exp map by straightest geodesics against the analytic oracles of docs/testing.md#what-tests-assert: straight
// segments on a jittered plane, the unrolled strip of a prism cylinder, great circles on an
// icosphere, generators of a cone; plus boundaries, degenerate triangles and the frame conversion.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "geoshift/geodesic.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

constexpr double kPi = std::numbers::pi;

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

struct Random {
  std::mt19937 engine{12345};
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(engine); }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(engine); }
  Vec3 bary() {
    Vec3 b(uniform(0.01, 1), uniform(0.01, 1), uniform(0.01, 1));
    return b / b.sum();
  }
};

bool validBary(const SurfacePoint& p) {
  return p.bary.allFinite() && p.bary.minCoeff() >= 0 && std::abs(p.bary.sum() - 1) < 1e-12;
}

// A face point whose position lies in [lo, hi]^2 of a plane mesh.
SurfacePoint facePointIn(const Mesh& m, Random& rng, double lo, double hi) {
  for (;;) {
    const SurfacePoint p{rng.index(m.faceCount()), rng.bary()};
    const Vec3 x = p.position(m);
    if (x.x() > lo && x.x() < hi && x.y() > lo && x.y() < hi) return p;
  }
}

// The vertex frame of an interior vertex of the z = 0 plane (θ = 2π): the plane turned so that
// angle 0 lies along halfedge(v).
Vec3 planeVertexDirection(const Mesh& m, int v, double phi) {
  const int h = m.halfedge(v);
  const Vec3 x = (m.position(m.head(h)) - m.position(v)).normalized();
  const Vec3 y = Vec3::UnitZ().cross(x);
  return std::cos(phi) * x + std::sin(phi) * y;
}

}  // namespace

TEST_CASE("on a jittered plane the exp map is a straight segment", "[expmap][plane]") {
  const Mesh m = build(shapes::grid(41, 0.2));
  const SurfaceGeometry geo(m);
  Random rng;

  SECTION("from face points") {
    for (int i = 0; i < 500; ++i) {
      const SurfacePoint p = facePointIn(m, rng, 0.3, 0.7);
      const double a = rng.uniform(0, 2 * kPi), len = rng.uniform(0.001, 0.28);
      const Vec2 v = len * Vec2(std::cos(a), std::sin(a));
      const ExpMapResult r = expMap(geo, p, v);
      REQUIRE_FALSE(r.hitBoundary);
      REQUIRE(validBary(r.end));
      REQUIRE((r.end.position(m) - (p.position(m) + geo.fromFaceFrame(p.face, v))).norm() < 1e-9);
      REQUIRE(r.length == Approx(len).epsilon(1e-12));
    }
  }
  SECTION("from interior vertices, in the vertex polar frame") {
    for (int i = 0; i < 300; ++i) {
      const int v = (10 + rng.index(21)) * 41 + 10 + rng.index(21);
      REQUIRE(geo.angleSum(v) == Approx(2 * kPi).epsilon(1e-12));
      const double phi = rng.uniform(0, 2 * kPi), len = rng.uniform(0.001, 0.2);
      const ExpMapResult r = expMap(geo, SurfacePoint::atVertex(m, v), len * Vec2(std::cos(phi), std::sin(phi)));
      REQUIRE_FALSE(r.hitBoundary);
      REQUIRE(validBary(r.end));
      REQUIRE((r.end.position(m) - (m.position(v) + len * planeVertexDirection(m, v, phi))).norm() < 1e-9);
    }
  }
  SECTION("a path aimed exactly at a vertex passes through it and goes on straight") {
    int aimed = 0, snapped = 0;
    while (aimed < 200) {
      const SurfacePoint p = facePointIn(m, rng, 0.35, 0.65);
      const int w = (9 + rng.index(23)) * 41 + 9 + rng.index(23);
      const Vec3 toW = m.position(w) - p.position(m);
      if (toW.norm() < 0.02 || toW.norm() > 0.2) continue;
      ++aimed;
      const Vec2 v = 1.5 * geo.toFaceFrame(p.face, toW);
      const ExpMapResult r = expMap(geo, p, v, {.recordPath = true});
      REQUIRE_FALSE(r.hitBoundary);
      REQUIRE((r.end.position(m) - (p.position(m) + 1.5 * toW)).norm() < 1e-9);
      for (const Vec3& x : r.path) snapped += (x - m.position(w)).norm() < 1e-14;
    }
    CHECK(snapped > 190);  // the path really went through the vertex, not next to it
  }
}

TEST_CASE("on a prism cylinder the exp map follows the unrolled strip", "[expmap][cylinder]") {
  const int sides = 32;
  const double height = 4;
  const Mesh m = build(shapes::cylinder(sides, 81, 1.0, height));
  const SurfaceGeometry geo(m);
  const double step = 2 * kPi / sides, width = 2 * std::sin(kPi / sides);
  auto corner = [&](int i) { return Vec3(std::cos(i * step), std::sin(i * step), 0); };
  auto column = [&](const Vec3& x) {
    double a = std::atan2(x.y(), x.x());
    if (a < 0) a += 2 * kPi;
    return std::min(static_cast<int>(a / step), sides - 1);
  };
  auto tangent = [&](int i) { return ((corner(i + 1) - corner(i)) / width).eval(); };
  // The isometry of the prism onto the strip [0, sides * width) × [0, height], and back.
  auto unroll = [&](const Vec3& x) {
    const int i = column(x);
    return Vec2(i * width + (x - corner(i)).dot(tangent(i)), x.z());
  };
  auto rollUp = [&](const Vec2& u) {
    const double c = std::floor(u.x() / width);
    const int i = ((static_cast<int>(c) % sides) + sides) % sides;
    return (corner(i) + (u.x() / width - c) * (corner(i + 1) - corner(i)) + u.y() * Vec3::UnitZ()).eval();
  };

  Random rng;
  for (int n = 0; n < 300; ++n) {
    SurfacePoint p{rng.index(m.faceCount()), rng.bary()};
    const Vec3 x = p.position(m);
    if (x.z() < 1.4 || x.z() > 2.6) continue;
    // A helix: a straight line of the strip that winds up to 1.3 times around.
    const double a = rng.uniform(-0.15, 0.15) + (rng.index(2) ? kPi : 0.0), len = rng.uniform(0.5, 8);
    const Vec3 d = std::cos(a) * tangent(column(x)) + std::sin(a) * Vec3::UnitZ();
    const Vec2 v = len * geo.toFaceFrame(p.face, d);
    const ExpMapResult r = expMap(geo, p, v);
    REQUIRE_FALSE(r.hitBoundary);
    REQUIRE(validBary(r.end));
    REQUIRE(r.facesCrossed > 0);
    const Vec3 expected = rollUp(unroll(x) + len * Vec2(std::cos(a), std::sin(a)));
    REQUIRE((r.end.position(m) - expected).norm() < 1e-9);
  }
}

namespace {

// Mean and max distance between exp_p(v) and the great-circle point cos(|v|/R) p + R sin(|v|/R) v̂
// (docs/testing.md#what-tests-assert) for traces of length πR/2 from random face points; p and v̂ are the start point and its
// direction pushed onto the sphere.
std::pair<double, double> sphereErrors(int level, double radius, int samples) {
  const Mesh m = build(shapes::icosphere(level, radius));
  const SurfaceGeometry geo(m);
  Random rng;
  double sum = 0, worst = 0;
  const double len = kPi * radius / 2;
  for (int i = 0; i < samples; ++i) {
    const SurfacePoint s{rng.index(m.faceCount()), rng.bary()};
    const double a = rng.uniform(0, 2 * kPi);
    const Vec2 v = len * Vec2(std::cos(a), std::sin(a));
    const ExpMapResult r = expMap(geo, s, v);
    REQUIRE(validBary(r.end));
    REQUIRE(r.length == Approx(len));
    const Vec3 p = radius * s.position(m).normalized();
    const Vec3 d = geo.fromFaceFrame(s.face, v);
    const Vec3 dir = (d - d.dot(p) / (radius * radius) * p).normalized();
    const Vec3 exact = std::cos(len / radius) * p + radius * std::sin(len / radius) * dir;
    const double e = (r.end.position(m) - exact).norm();
    sum += e;
    worst = std::max(worst, e);
  }
  return {sum / samples, worst};
}

}  // namespace

TEST_CASE("on an icosphere the exp map converges to great circles", "[expmap][sphere]") {
  const double R = 2.0;
  const auto [mean3, max3] = sphereErrors(3, R, 300);
  const auto [mean4, max4] = sphereErrors(4, R, 300);
  const auto [mean5, max5] = sphereErrors(5, R, 300);
  INFO("mean/max error / R: level 3 " << mean3 / R << " / " << max3 / R << ", level 4 " << mean4 / R << " / "
                                      << max4 / R << ", level 5 " << mean5 / R << " / " << max5 / R);
  CHECK(max5 < 1e-2 * R);
  CHECK(mean4 < 0.75 * mean3);
  CHECK(mean5 < 0.75 * mean4);
  CHECK(max5 < max3);
}

namespace {

// A cone with its apex at (0, 0, 1) over an irregular polygon, cut into `rings` rings along its
// generators: every apex triangle and the trapezoids under it lie in one plane, so the generators
// are straight on the surface and the only curvature is the apex's angle defect.
TriangleSoup cone(int sides, int rings) {
  TriangleSoup s;
  s.positions.emplace_back(0, 0, 1);
  for (int k = 1; k <= rings; ++k) {
    for (int i = 0; i < sides; ++i) {
      const double a = 2 * kPi * (i + 0.3 * std::sin(3.0 * i)) / sides, r = 0.5 * k / rings;
      s.positions.emplace_back(r * std::cos(a), r * std::sin(a), 1.0 - static_cast<double>(k) / rings);
    }
  }
  auto at = [&](int k, int i) { return k == 0 ? 0 : 1 + (k - 1) * sides + (i % sides); };
  for (int i = 0; i < sides; ++i) s.faces.push_back({0, at(1, i), at(1, i + 1)});
  for (int k = 1; k < rings; ++k) {
    for (int i = 0; i < sides; ++i) {
      s.faces.push_back({at(k, i), at(k + 1, i), at(k + 1, i + 1)});
      s.faces.push_back({at(k, i), at(k + 1, i + 1), at(k, i + 1)});
    }
  }
  return s;
}

double distanceToLine(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 d = (b - a).normalized();
  return ((x - a) - (x - a).dot(d) * d).norm();
}

}  // namespace

TEST_CASE("from a cone apex the exp map follows generators", "[expmap][cone]") {
  const MeshBuild built = buildMesh(cone(9, 4));
  REQUIRE(built.report.clean());
  const Mesh& m = built.mesh;
  const SurfaceGeometry geo(m);
  const int apex = 0;
  REQUIRE_FALSE(m.isBoundaryVertex(apex));
  REQUIRE(geo.angleSum(apex) < 2 * kPi - 0.5);
  const SurfacePoint start = SurfacePoint::atVertex(m, apex);
  const Vec3 tip = m.position(apex);

  SECTION("at the normalised angle of an edge, along that edge and on through the ring vertices") {
    int edges = 0;
    m.forEachOutgoing(apex, [&](int h) {
      ++edges;
      const Vec3 foot = m.position(m.head(h));
      const double slant = std::sqrt(0.25 + 1.0);  // to the last ring
      for (double fraction : {0.1, 0.2, 0.45, 0.6, 0.95}) {
        const double phi = geo.polarAngle(h), len = fraction * slant;
        const ExpMapResult r = expMap(geo, start, len * Vec2(std::cos(phi), std::sin(phi)));
        REQUIRE_FALSE(r.hitBoundary);
        const Vec3 x = r.end.position(m);
        REQUIRE(distanceToLine(x, tip, foot) < 1e-9);
        REQUIRE((x - tip).norm() == Approx(len).epsilon(1e-9));
        REQUIRE((x - tip).dot(foot - tip) > 0);
      }
    });
    CHECK(edges == 9);
  }
  SECTION("between edges, at the true angle (φ - polarAngle) θ / 2π from the wedge's first edge") {
    Random rng;
    for (int i = 0; i < 200; ++i) {
      const double phi = rng.uniform(0, 2 * kPi), len = rng.uniform(0.05, 1.0);
      int wedge = m.halfedge(apex);
      m.forEachOutgoing(apex, [&](int h) {
        if (geo.polarAngle(h) <= phi) wedge = h;
      });
      const double beta = (phi - geo.polarAngle(wedge)) * geo.angleSum(apex) / (2 * kPi);
      const int f = Mesh::faceOf(wedge);
      const Vec3 x = (m.position(m.head(wedge)) - tip).normalized();
      const Vec3 dir = std::cos(beta) * x + std::sin(beta) * geo.faceNormal(f).cross(x);
      const ExpMapResult r = expMap(geo, start, len * Vec2(std::cos(phi), std::sin(phi)));
      REQUIRE_FALSE(r.hitBoundary);
      REQUIRE((r.end.position(m) - (tip + len * dir)).norm() < 1e-9);
    }
  }
  SECTION("through the apex: out at θ/2 from the way in on both sides (normalised angle + π)") {
    // Where a ray from the apex at normalised angle phi is after len, from the wedge that holds phi.
    auto rayPoint = [&](double phi, double len) {
      int wedge = m.halfedge(apex);
      m.forEachOutgoing(apex, [&](int h) {
        if (geo.polarAngle(h) <= phi) wedge = h;
      });
      const double beta = (phi - geo.polarAngle(wedge)) / geo.angleScale(apex);
      const Vec3 x = (m.position(m.head(wedge)) - tip).normalized();
      return (tip + len * (std::cos(beta) * x + std::sin(beta) * geo.faceNormal(Mesh::faceOf(wedge)).cross(x))).eval();
    };
    Random rng;
    int through = 0;
    m.forEachOutgoing(apex, [&](int h) {
      for (int i = 0; i < 20; ++i) {
        const SurfacePoint p{Mesh::faceOf(h), rng.bary()};
        const Vec3 x = p.position(m), e = m.position(m.head(h)) - tip;
        const Vec3 n = geo.faceNormal(p.face);
        const double phiIn = geo.polarAngle(h) + std::atan2(n.dot(e.cross(x - tip)), e.dot(x - tip)) * geo.angleScale(apex);
        const double beyond = rng.uniform(0.05, 0.8);
        const Vec2 v = ((x - tip).norm() + beyond) * geo.toFaceFrame(p.face, (tip - x).normalized());
        const ExpMapResult r = expMap(geo, p, v, {.recordPath = true});
        REQUIRE_FALSE(r.hitBoundary);
        for (const Vec3& y : r.path) through += (y - tip).norm() < 1e-14;
        REQUIRE((r.end.position(m) - rayPoint(std::fmod(phiIn + kPi, 2 * kPi), beyond)).norm() < 1e-9);
      }
    });
    CHECK(through == 9 * 20);
  }
  SECTION("tangentFromDirection gives each edge of the point's face its polar angle") {
    m.forEachOutgoing(apex, [&](int h) {
      const int next = m.ccwOutgoing(h);
      const SurfacePoint corner{Mesh::faceOf(h), Vec3::Unit(h % 3)};
      const Vec2 along = tangentFromDirection(geo, corner, 2.0 * (m.position(m.head(h)) - tip));
      CHECK(along.norm() == Approx(2.0 * geo.length(h)));
      CHECK(std::atan2(along.y(), along.x()) == Approx(std::remainder(geo.polarAngle(h), 2 * kPi)).margin(1e-12));
      const Vec2 far = tangentFromDirection(geo, corner, m.position(m.tail(Mesh::prev(h))) - tip);
      CHECK(std::cos(std::atan2(far.y(), far.x()) - geo.polarAngle(next)) == Approx(1.0).margin(1e-12));
    });
  }
}

TEST_CASE("the exp map stops at the boundary", "[expmap][boundary]") {
  const Mesh m = build(shapes::grid(21, 0.2));
  const SurfaceGeometry geo(m);
  Random rng;

  SECTION("toward the boundary from inside") {
    for (int i = 0; i < 200; ++i) {
      const SurfacePoint p = facePointIn(m, rng, 0.2, 0.8);
      const double a = rng.uniform(0, 2 * kPi);
      const Vec2 v = 2.0 * Vec2(std::cos(a), std::sin(a));
      const ExpMapResult r = expMap(geo, p, v);
      REQUIRE(r.hitBoundary);
      REQUIRE(r.length < 2.0);
      REQUIRE(validBary(r.end));
      const Vec3 x = r.end.position(m);
      REQUIRE(std::min({x.x(), x.y(), 1 - x.x(), 1 - x.y()}) < 1e-12);
      REQUIRE((x - (p.position(m) + r.length / 2.0 * geo.fromFaceFrame(p.face, v))).norm() < 1e-9);
      // On an edge of its face that is a boundary edge (or at a boundary vertex).
      bool onBoundaryEdge = false;
      for (int k = 0; k < 3; ++k)
        onBoundaryEdge |= r.end.bary[k] == 0 && m.twin(3 * r.end.face + (k + 1) % 3) < 0;
      const int corner = r.end.vertex(m);
      REQUIRE((onBoundaryEdge || (corner >= 0 && m.isBoundaryVertex(corner))));
    }
  }
  SECTION("a path through a boundary vertex stops there") {
    for (const int w : {0, 7, 20, 13 * 21, 20 * 21 + 4}) {
      const SurfacePoint p = facePointIn(m, rng, 0.3, 0.7);
      const Vec3 toW = m.position(w) - p.position(m);
      const ExpMapResult r = expMap(geo, p, 1.2 * geo.toFaceFrame(p.face, toW));
      CHECK(r.hitBoundary);
      CHECK(r.end.vertex(m) == w);
      CHECK(r.length == Approx(toW.norm()).epsilon(1e-12));
    }
  }
  SECTION("from a boundary edge: outward stops at once, inward is a segment") {
    int h = 0;
    while (m.twin(h) >= 0 || m.position(m.tail(h)).y() != 0 || m.position(m.head(h)).y() != 0) ++h;  // y = 0, +x
    const SurfacePoint p = SurfacePoint::onEdge(m, h, 0.4);
    const Vec2 out = geo.toFaceFrame(p.face, Vec3(0.3, -0.5, 0));
    const ExpMapResult r = expMap(geo, p, out);
    CHECK(r.hitBoundary);
    CHECK(r.length == 0);
    CHECK((r.end.position(m) - p.position(m)).norm() < 1e-15);
    const Vec2 in = geo.toFaceFrame(p.face, Vec3(0.3, 0.5, 0));
    const ExpMapResult s = expMap(geo, p, in);
    CHECK_FALSE(s.hitBoundary);
    CHECK((s.end.position(m) - (p.position(m) + Vec3(0.3, 0.5, 0))).norm() < 1e-9);
  }
  SECTION("from boundary vertices: angles run over [0, θ], beyond that the vector points off") {
    for (const int v : {7, 0, 20 * 21 + 20, 13 * 21}) {  // a side vertex, corners, the x = 0 side
      const double theta = geo.angleSum(v);
      REQUIRE(m.isBoundaryVertex(v));
      const int h = m.halfedge(v);
      const Vec3 x = (m.position(m.head(h)) - m.position(v)).normalized();
      const Vec3 y = Vec3::UnitZ().cross(x);
      for (int i = 0; i < 50; ++i) {
        const double phi = rng.uniform(0, theta), len = rng.uniform(0.01, 0.3);
        const ExpMapResult r = expMap(geo, SurfacePoint::atVertex(m, v), len * Vec2(std::cos(phi), std::sin(phi)));
        REQUIRE_FALSE(r.hitBoundary);
        REQUIRE((r.end.position(m) - (m.position(v) + len * (std::cos(phi) * x + std::sin(phi) * y))).norm() <
                1e-9);
        const double off = rng.uniform(theta + 1e-3, 2 * kPi - 1e-3);
        const ExpMapResult o = expMap(geo, SurfacePoint::atVertex(m, v), len * Vec2(std::cos(off), std::sin(off)));
        REQUIRE(o.hitBoundary);
        REQUIRE(o.length == 0);
        REQUIRE(o.end.vertex(m) == v);
      }
    }
  }
}

TEST_CASE("the exp map from a point on an interior edge goes to either side", "[expmap][edge]") {
  const Mesh m = build(shapes::grid(41, 0.2));
  const SurfaceGeometry geo(m);
  Random rng;
  for (int i = 0; i < 300; ++i) {
    const SurfacePoint q = facePointIn(m, rng, 0.3, 0.7);
    const int h = 3 * q.face + rng.index(3);
    REQUIRE(m.twin(h) >= 0);
    const SurfacePoint p = SurfacePoint::onEdge(m, h, rng.uniform(0.05, 0.95));
    const double a = rng.uniform(0, 2 * kPi), len = rng.uniform(0.01, 0.25);
    const Vec2 v = len * Vec2(std::cos(a), std::sin(a));
    const ExpMapResult r = expMap(geo, p, v);
    REQUIRE_FALSE(r.hitBoundary);
    REQUIRE((r.end.position(m) - (p.position(m) + geo.fromFaceFrame(p.face, v))).norm() < 1e-9);
  }
}

TEST_CASE("the exp map survives degenerate triangles and grazing directions", "[expmap][degenerate]") {
  Random rng;
  SECTION("a planar strip with needles and a near-zero edge: still straight segments") {
    TriangleSoup s;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i <= 6; ++i) s.positions.emplace_back(i, j, 0);
    s.positions[3 + 7] = Vec3(3, 1e-9, 0);   // top vertex almost on the bottom side: needles
    s.positions[5] = Vec3(4 + 1e-10, 0, 0);  // an edge of length 1e-10
    for (int i = 0; i < 6; ++i) {
      s.faces.push_back({i, i + 1, i + 8});
      s.faces.push_back({i, i + 8, i + 7});
    }
    const MeshBuild built = buildMesh(s);
    REQUIRE(built.report.clean());
    const Mesh& m = built.mesh;
    const SurfaceGeometry geo(m);
    for (int i = 0; i < 2000; ++i) {
      const SurfacePoint p{rng.index(m.faceCount()), rng.bary()};
      const double a = rng.uniform(0, 2 * kPi), len = rng.uniform(0.1, 8);
      const Vec2 v = len * Vec2(std::cos(a), std::sin(a));
      const ExpMapResult r = expMap(geo, p, v);
      REQUIRE(validBary(r.end));
      REQUIRE(std::isfinite(r.length));
      REQUIRE(r.length <= len * (1 + 1e-12));
      const Vec3 expected = p.position(m) + r.length / len * geo.fromFaceFrame(p.face, v);
      REQUIRE((r.end.position(m) - expected).norm() < 1e-6);
    }
  }
  SECTION("zero-length edges and zero-area faces made after construction: finite and terminating") {
    Mesh m = build(shapes::grid(11));
    m.position(5 * 11 + 5) = m.position(5 * 11 + 6);  // zero-length edge
    const Face flat = m.face(60);                      // a corner onto the opposite edge: zero area
    m.position(flat[0]) = 0.5 * (m.position(flat[1]) + m.position(flat[2]));
    const SurfaceGeometry geo(m);
    for (int i = 0; i < 2000; ++i) {
      const SurfacePoint p{rng.index(m.faceCount()), rng.bary()};
      const double a = rng.uniform(0, 2 * kPi), len = rng.uniform(0.01, 2);
      const ExpMapResult r = expMap(geo, p, len * Vec2(std::cos(a), std::sin(a)));
      REQUIRE(validBary(r.end));
      REQUIRE(r.end.position(m).allFinite());
      REQUIRE(r.length <= len * (1 + 1e-12));
    }
    for (const int v : {5 * 11 + 5, 5 * 11 + 6, flat[0]}) {
      const ExpMapResult r = expMap(geo, SurfacePoint::atVertex(m, v), Vec2(0.3, 0.2));
      REQUIRE(validBary(r.end));
      REQUIRE(r.end.position(m).allFinite());
    }
  }
  SECTION("grazing: along grid lines and diagonals through rows of vertices") {
    const Mesh m = build(shapes::grid(11));
    const SurfaceGeometry geo(m);
    int grazing = 0;
    for (const Vec3 d : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(1, 1, 0), Vec3(-1, -1, 0)}) {
      for (int h = 0; h < m.halfedgeCount(); ++h) {
        const Vec3 a = m.position(m.tail(h)), b = m.position(m.head(h));
        if ((b - a).normalized().dot(d.normalized()) < 1 - 1e-12) continue;
        const SurfacePoint p = SurfacePoint::onEdge(m, h, 0.3);
        const Vec3 x = p.position(m), far = x + 0.25 * d.normalized();
        if (std::min({a.x(), a.y(), far.x(), far.y()}) < 0.1 || std::max({a.x(), a.y(), far.x(), far.y()}) > 0.9)
          continue;
        ++grazing;
        const Vec2 v = geo.toFaceFrame(p.face, 0.25 * d.normalized());
        for (const Vec2 w : {v, Vec2(v + Vec2(-v.y(), v.x()) * 1e-14), Vec2(v - Vec2(-v.y(), v.x()) * 1e-14)}) {
          const ExpMapResult r = expMap(geo, p, w);
          const Vec3 e = r.end.position(m);
          REQUIRE_FALSE(r.hitBoundary);
          REQUIRE((e - (x + 0.25 * d.normalized())).norm() < 1e-9);
        }
        const ExpMapResult fromTail = expMap(geo, SurfacePoint::atVertex(m, m.tail(h)),
                                             tangentFromDirection(geo, SurfacePoint{Mesh::faceOf(h), Vec3::Unit(h % 3)},
                                                                  0.25 * d.normalized()));
        REQUIRE((fromTail.end.position(m) - (a + 0.25 * d.normalized())).norm() < 1e-9);
      }
    }
    CHECK(grazing > 100);
  }
}

TEST_CASE("tangentFromDirection then expMap reaches the target on a plane", "[expmap][tangent]") {
  const Mesh m = build(shapes::grid(41, 0.2));
  const SurfaceGeometry geo(m);
  Random rng;
  for (int i = 0; i < 300; ++i) {
    const SurfacePoint fp = facePointIn(m, rng, 0.3, 0.7);
    const int v = (10 + rng.index(21)) * 41 + 10 + rng.index(21);
    // At a vertex the point's face is any face around it, not only the face of halfedge(v).
    SurfacePoint vp;
    m.forEachOutgoing(v, [&](int h) {
      if (vp.face < 0 || rng.index(3) == 0) vp = SurfacePoint{Mesh::faceOf(h), Vec3::Unit(h % 3)};
    });
    for (const SurfacePoint& p : {fp, vp}) {
      const Vec3 target = p.position(m) + Vec3(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), 0);
      const Vec3 toTarget = target - p.position(m);
      // A normal component is dropped by the projection.
      const Vec2 t = tangentFromDirection(geo, p, toTarget + Vec3(0, 0, 0.7));
      REQUIRE(t.norm() == Approx(toTarget.norm()).epsilon(1e-12));
      const ExpMapResult r = expMap(geo, p, t);
      REQUIRE((r.end.position(m) - target).norm() < 1e-9);
    }
  }
  CHECK(tangentFromDirection(geo, SurfacePoint{0, Vec3(0.2, 0.3, 0.5)}, Vec3(0, 0, 2)).norm() == 0);
}

TEST_CASE("a zero vector returns the start point", "[expmap][zero]") {
  const Mesh m = build(shapes::icosphere(2));
  const SurfaceGeometry geo(m);
  for (const SurfacePoint& p : {SurfacePoint{4, Vec3(0.2, 0.3, 0.5)}, SurfacePoint::atVertex(m, 7),
                                SurfacePoint::onEdge(m, 5, 0.25)}) {
    const ExpMapResult r = expMap(geo, p, Vec2::Zero(), {.recordPath = true});
    CHECK(r.end.face == p.face);
    CHECK((r.end.bary - p.bary).norm() < 1e-15);
    CHECK(r.length == 0);
    CHECK(r.facesCrossed == 0);
    CHECK_FALSE(r.hitBoundary);
    CHECK(r.path.size() == 2);
  }
}

TEST_CASE("the recorded path runs from the start to the end through every crossing", "[expmap][path]") {
  const Mesh m = build(shapes::icosphere(3));
  const SurfaceGeometry geo(m);
  const SurfacePoint p{10, Vec3(0.2, 0.3, 0.5)};
  const ExpMapResult r = expMap(geo, p, Vec2(1.3, 0.4), {.recordPath = true});
  REQUIRE(r.path.size() == static_cast<size_t>(r.facesCrossed) + 2);
  CHECK((r.path.front() - p.position(m)).norm() < 1e-15);
  CHECK((r.path.back() - r.end.position(m)).norm() < 1e-15);
  double polyline = 0;
  for (size_t i = 1; i < r.path.size(); ++i) polyline += (r.path[i] - r.path[i - 1]).norm();
  CHECK(polyline == Approx(r.length).epsilon(1e-12));
  CHECK(expMap(geo, p, Vec2(1.3, 0.4)).path.empty());
}

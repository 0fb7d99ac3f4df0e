// Log map (DGPC, docs/algorithms.md#log-map) against analytic answers (docs/testing.md#what-tests-assert): exact polar coordinates on
// flat surfaces (jittered plane, prism cylinder, flat cone), convergence on the sphere.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

constexpr double kPi = std::numbers::pi;

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

double wrap(double t) {
  t = std::fmod(t, 2 * kPi);
  return t < 0 ? t + 2 * kPi : t;
}

double angleOf(const Vec2& v) { return std::atan2(v.y(), v.x()); }

const LogMapEntry* find(const std::vector<LogMapEntry>& entries, int v) {
  for (const LogMapEntry& e : entries)
    if (e.vertex == v) return &e;
  return nullptr;
}

void requireSortedAndFinite(const std::vector<LogMapEntry>& entries, double radius) {
  for (size_t i = 0; i < entries.size(); ++i) {
    REQUIRE(std::isfinite(entries[i].distance));
    REQUIRE(std::isfinite(entries[i].angle));
    REQUIRE(entries[i].angle >= 0);
    REQUIRE(entries[i].angle < 2 * kPi);
    REQUIRE(entries[i].distance <= radius);
    if (i > 0) REQUIRE(entries[i - 1].distance <= entries[i].distance);
  }
}

// Flat surfaces: `planar(v)` is v's position in an isometric unfolding around the source. For a
// vertex source the expected frame has angle 0 along halfedge(s) and no scale (θ(s) = 2π inside,
// unscaled on the boundary). Checks every vertex `inside` accepts; returns how many were checked.
int checkVertexSourceFlat(const Mesh& mesh, int s, double radius, const std::function<Vec2(int)>& planar,
                          const std::function<bool(int)>& inside) {
  const SurfaceGeometry geometry(mesh);
  LogMap logMap(geometry);
  const auto& entries = logMap.computeFromVertex(s, radius);
  requireSortedAndFinite(entries, radius);
  REQUIRE(entries.front().vertex == s);
  REQUIRE(entries.front().distance == 0);
  const Vec2 origin = planar(s);
  const double reference = angleOf(planar(mesh.head(mesh.halfedge(s))) - origin);
  int checked = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vec2 d = planar(v) - origin;
    if (v == s || !inside(v) || d.norm() > radius - 1e-9) continue;
    const LogMapEntry* e = find(entries, v);
    REQUIRE(e != nullptr);
    const double a = wrap(angleOf(d) - reference);
    const Vec2 expected = d.norm() * Vec2(std::cos(a), std::sin(a));
    INFO("vertex " << v << " U " << e->distance << " expected " << d.norm());
    REQUIRE(std::abs(e->distance - d.norm()) < 1e-9);
    REQUIRE((e->coords() - expected).norm() < 1e-9);
    REQUIRE(e->angle <= geometry.angleSum(s) + 1e-12);
    ++checked;
  }
  return checked;
}

// A face or edge point on the z = 0 plane: log coordinates are the face-frame vector to the vertex.
int checkPointSourcePlane(const Mesh& mesh, const SurfacePoint& p, double radius, double margin) {
  const SurfaceGeometry geometry(mesh);
  LogMap logMap(geometry);
  const auto& entries = logMap.compute(p, radius);
  requireSortedAndFinite(entries, radius);
  const Vec3 origin = p.position(mesh);
  int checked = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vec3 q = mesh.position(v);
    const double dist = (q - origin).norm();
    if (dist > radius - 1e-9 || std::min({q.x(), q.y(), 1 - q.x(), 1 - q.y()}) < margin) continue;
    const LogMapEntry* e = find(entries, v);
    REQUIRE(e != nullptr);
    INFO("vertex " << v);
    REQUIRE(std::abs(e->distance - dist) < 1e-9);
    REQUIRE((e->coords() - geometry.toFaceFrame(p.face, q - origin)).norm() < 1e-9);
    ++checked;
  }
  return checked;
}

Vec2 xy(const Mesh& mesh, int v) { return mesh.position(v).head<2>(); }

// A face of the 41×41 grid near the centre (the grid's faces run row by row, two per quad).
int centreFace(int n) { return 2 * ((n / 2) * (n - 1) + n / 2); }

}  // namespace

TEST_CASE("log map on a jittered plane is exact polar coordinates", "[logmap][plane]") {
  const Mesh mesh = build(shapes::grid(41, 0.2));
  const auto interior = [&](int v) {
    const Vec3& q = mesh.position(v);
    return std::min({q.x(), q.y(), 1 - q.x(), 1 - q.y()}) > 0.06;
  };
  SECTION("interior vertex source") {
    const int s = 20 * 41 + 20;
    CHECK(checkVertexSourceFlat(mesh, s, 0.3, [&](int v) { return xy(mesh, v); }, interior) > 400);
  }
  SECTION("interior face source") {
    const SurfacePoint p = SurfacePoint::inFace(mesh, centreFace(41), Vec3(0.2, 0.3, 0.5));
    CHECK(checkPointSourcePlane(mesh, p, 0.3, 0.06) > 400);
  }
  SECTION("edge source: no wrap glitch across the edge, in either face's frame") {
    const int f = centreFace(41);
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * f + k;
      REQUIRE(mesh.twin(h) >= 0);
      CHECK(checkPointSourcePlane(mesh, SurfacePoint::onEdge(mesh, h, 0.4), 0.3, 0.06) > 400);
      CHECK(checkPointSourcePlane(mesh, SurfacePoint::onEdge(mesh, mesh.twin(h), 0.6), 0.3, 0.06) > 400);
    }
  }
}

TEST_CASE("log map from a boundary vertex of the plane", "[logmap][plane][boundary]") {
  const Mesh mesh = build(shapes::grid(41, 0.2));
  const auto all = [](int) { return true; };
  const auto planar = [&](int v) { return xy(mesh, v); };
  const SurfaceGeometry geometry(mesh);
  SECTION("corner: angles in [0, π/2]") {
    REQUIRE(geometry.angleSum(0) == Approx(kPi / 2));
    CHECK(checkVertexSourceFlat(mesh, 0, 0.4, planar, all) > 150);
  }
  SECTION("edge: angles in [0, π]") {
    const int s = 20;  // (0.5, 0) on the bottom edge
    REQUIRE(mesh.isBoundaryVertex(s));
    REQUIRE(geometry.angleSum(s) == Approx(kPi));
    CHECK(checkVertexSourceFlat(mesh, s, 0.3, planar, all) > 200);
  }
}

TEST_CASE("log map through vertices of high valence is exact on flat fans", "[logmap][plane][valence]") {
  // Flat fans whose centre has more neighbours than a ring record holds inline (the solver keeps
  // those apart): a disc of 12 uneven sectors in two rings, whose centre is interior (a closed ring
  // of 12), and a half-disc of 10 sectors whose centre sits on the boundary (an open ring of 11).
  const auto fan = [](int sectors, double span) {
    TriangleSoup soup;
    soup.positions.push_back(Vec3::Zero());
    const bool closed = span == 2 * kPi;
    const int spokes = closed ? sectors : sectors + 1;
    for (int r = 1; r <= 2; ++r)
      for (int i = 0; i < spokes; ++i) {
        const double phi = span * (i + 0.25 * std::sin(3.0 * i) * (closed || (i > 0 && i < sectors))) / sectors;
        soup.positions.push_back(r * Vec3(std::cos(phi), std::sin(phi), 0));
      }
    for (int i = 0; i < sectors; ++i) {
      const int a = 1 + i, b = 1 + (i + 1) % spokes;
      soup.faces.push_back({0, a, b});
      soup.faces.push_back({a, a + spokes, b + spokes});
      soup.faces.push_back({a, b + spokes, b});
    }
    return soup;
  };
  const auto planar = [](const Mesh& mesh) { return [&mesh](int v) { return xy(mesh, v); }; };
  const auto all = [](int) { return true; };
  SECTION("interior centre of 12 neighbours, from the centre and from a face point") {
    const Mesh mesh = build(fan(12, 2 * kPi));
    REQUIRE(mesh.valence(0) == 12);
    REQUIRE_FALSE(mesh.isBoundaryVertex(0));
    CHECK(checkVertexSourceFlat(mesh, 0, 3.0, planar(mesh), all) == 24);
    // From a point of an outer face: every vertex is reached straight, through or around the centre.
    const SurfaceGeometry geometry(mesh);
    LogMap logMap(geometry);
    const int f = 3 * 5 + 1;  // the outer face of sector 5
    const SurfacePoint p = SurfacePoint::inFace(mesh, f, Vec3(0.3, 0.3, 0.4));
    const auto& entries = logMap.compute(p, 5.0);
    REQUIRE(entries.size() == 25);
    for (const LogMapEntry& e : entries) {
      const Vec3 d = mesh.position(e.vertex) - p.position(mesh);
      INFO("vertex " << e.vertex);
      CHECK(std::abs(e.distance - d.norm()) < 1e-9);
      CHECK((e.coords() - geometry.toFaceFrame(f, d)).norm() < 1e-9);
    }
  }
  SECTION("boundary centre of 11 neighbours: angles in [0, π]") {
    const Mesh mesh = build(fan(10, kPi));
    REQUIRE(mesh.valence(0) == 11);
    REQUIRE(mesh.isBoundaryVertex(0));
    CHECK(checkVertexSourceFlat(mesh, 0, 3.0, planar(mesh), all) == 22);
    // And from a vertex of the rim, whose straight lines to the far side pass by the centre.
    CHECK(checkVertexSourceFlat(mesh, 1 + 11 + 5, 5.0, planar(mesh), all) == 22);
  }
}

TEST_CASE("log map on a prism cylinder matches the unrolled plane", "[logmap][cylinder]") {
  const int sides = 16, rings = 41;
  const double height = 8;
  const MeshBuild b = buildMesh(shapes::cylinder(sides, rings, 1.0, height));
  const Mesh& mesh = b.mesh;
  const double width = 2 * std::sin(kPi / sides);  // perimeter 2mR sin(π/m)
  std::vector<Vec2> unrolled(mesh.vertexCount());
  for (int c = 0; c < sides * rings; ++c) {
    // Side index relative to the source's column, taken the short way round: no wrapping paths.
    int i = c % sides;
    if (i > sides / 2) i -= sides;
    unrolled[b.vertexOf[c]] = Vec2(i * width, height * (c / sides) / (rings - 1));
  }
  const int s = b.vertexOf[(rings / 2) * sides];
  const double radius = 0.45 * sides * width;  // < half the perimeter: nothing meets round the back
  CHECK(checkVertexSourceFlat(mesh, s, radius, [&](int v) { return unrolled[v]; }, [](int) { return true; }) > 100);
}

TEST_CASE("log map converges to great-circle distances on the icosphere", "[logmap][sphere]") {
  const Vec3 direction = Vec3(0.3, 0.5, 0.8).normalized();
  double previousDistance = 0, previousAngle = 0;
  for (int level = 3; level <= 5; ++level) {
    const Mesh mesh = build(shapes::icosphere(level));
    const SurfaceGeometry geometry(mesh);
    // The face whose centroid is nearest the fixed direction, so the source is comparable across levels.
    int f = 0;
    double best = -2;
    for (int g = 0; g < mesh.faceCount(); ++g) {
      const Face& t = mesh.face(g);
      const double c = (mesh.position(t[0]) + mesh.position(t[1]) + mesh.position(t[2])).normalized().dot(direction);
      if (c > best) best = c, f = g;
    }
    const SurfacePoint p = SurfacePoint::inFace(mesh, f, Vec3::Constant(1.0 / 3));
    const Vec3 origin = p.position(mesh).normalized();
    LogMap logMap(geometry);
    const auto& entries = logMap.compute(p, 1.0);
    requireSortedAndFinite(entries, 1.0);
    double distanceError = 0, angleError = 0;
    for (const LogMapEntry& e : entries) {
      const Vec3& q = mesh.position(e.vertex);
      distanceError = std::max(distanceError, std::abs(e.distance - std::acos(std::clamp(origin.dot(q), -1.0, 1.0))));
      // The great circle's initial direction, in the face frame; ill-posed right next to the source.
      if (e.distance < 3 * geometry.averageEdgeLength()) continue;
      const double expected = angleOf(geometry.toFaceFrame(f, q - origin.dot(q) * origin));
      const double diff = std::abs(wrap(e.angle - expected));
      angleError = std::max(angleError, std::min(diff, 2 * kPi - diff));
    }
    WARN("icosphere level " << level << ": " << entries.size() << " entries, max |U - acos| = " << distanceError
                            << ", max angle error = " << angleError);
    CHECK(angleError < 0.05);
    if (level > 3) {
      CHECK(distanceError < 0.7 * previousDistance);
      CHECK(angleError < 0.9 * previousAngle);
    }
    previousDistance = distanceError;
    previousAngle = angleError;
  }
}

TEST_CASE("log map at a cone apex normalises the one-ring to [0, 2π)", "[logmap][cone]") {
  // A pyramid with two rings of 7 vertices, the outer a scaled copy of the inner, so every sector is
  // one plane through the apex: intrinsically a flat cone of angle θ < 2π.
  const int n = 7;
  TriangleSoup soup;
  soup.positions.push_back(Vec3::Zero());
  for (int r = 1; r <= 2; ++r)
    for (int i = 0; i < n; ++i) {
      const double phi = 2 * kPi * i / n + 0.3 * std::sin(i);  // uneven sectors
      soup.positions.push_back(r * Vec3(std::cos(phi), std::sin(phi), -0.8));
    }
  for (int i = 0; i < n; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % n;
    soup.faces.push_back({0, a, b});
    soup.faces.push_back({a, a + n, b + n});
    soup.faces.push_back({a, b + n, b});
  }
  const Mesh mesh = build(soup);
  const SurfaceGeometry geometry(mesh);
  REQUIRE(geometry.angleSum(0) < 2 * kPi - 0.5);
  LogMap logMap(geometry);
  const auto& entries = logMap.computeFromVertex(0, 10.0);
  REQUIRE(entries.size() == static_cast<size_t>(2 * n + 1));
  double lo = 10, hi = -1;
  mesh.forEachOutgoing(0, [&](int h) {
    const LogMapEntry* e = find(entries, mesh.head(h));
    REQUIRE(e != nullptr);
    CHECK(e->angle == Approx(geometry.polarAngle(h)).margin(1e-12));
    CHECK(e->distance == Approx(geometry.length(h)).epsilon(1e-14));
    lo = std::min(lo, e->angle);
    hi = std::max(hi, e->angle);
  });
  CHECK(lo == 0);
  CHECK(hi < 2 * kPi);
  CHECK(hi > 2 * kPi * (n - 1) / n - 1.0);  // spread over the circle, not squeezed into θ(apex)
  // Each outer vertex lies on the generator through its inner vertex: same angle, distance |q|.
  for (int i = 0; i < n; ++i) {
    const LogMapEntry* inner = find(entries, 1 + i);
    const LogMapEntry* outer = find(entries, 1 + n + i);
    REQUIRE(outer != nullptr);
    CHECK(outer->distance == Approx(mesh.position(1 + n + i).norm()).epsilon(1e-12));
    CHECK(std::abs(outer->angle - inner->angle) < 1e-9);
  }
}

TEST_CASE("log map solver reuse resets between calls", "[logmap][reuse]") {
  const Mesh mesh = build(shapes::grid(81, 0.2));
  const SurfaceGeometry geometry(mesh);
  LogMap shared(geometry);
  const SurfacePoint a = SurfacePoint::inFace(mesh, centreFace(81), Vec3(0.1, 0.6, 0.3));
  const SurfacePoint b = SurfacePoint::inFace(mesh, centreFace(81) + 2 * 7 + 1, Vec3(0.5, 0.25, 0.25));
  const auto same = [](const std::vector<LogMapEntry>& x, const std::vector<LogMapEntry>& y) {
    REQUIRE(x.size() == y.size());
    for (size_t i = 0; i < x.size(); ++i) {
      CHECK(x[i].vertex == y[i].vertex);
      CHECK(x[i].distance == y[i].distance);
      CHECK(x[i].angle == y[i].angle);
    }
  };
  const std::vector<LogMapEntry> first = shared.compute(a, 0.2);
  const std::vector<LogMapEntry> second = shared.compute(b, 0.15);
  const std::vector<LogMapEntry> third = shared.computeFromVertex(40 * 81 + 45, 0.1);
  const std::vector<LogMapEntry> again = shared.compute(a, 0.2);
  LogMap fresh1(geometry), fresh2(geometry), fresh3(geometry);
  same(second, fresh1.compute(b, 0.15));
  same(third, fresh2.computeFromVertex(40 * 81 + 45, 0.1));
  same(first, again);
  same(first, fresh3.compute(a, 0.2));
  same(first, logMap(mesh, a, 0.2));

  // Entry count grows as the disc's area, ~R².
  const double n1 = static_cast<double>(shared.compute(a, 0.1).size());
  const double n2 = static_cast<double>(shared.compute(a, 0.2).size());
  const double n4 = static_cast<double>(shared.compute(a, 0.4).size());
  CHECK(n2 / n1 == Approx(4).epsilon(0.12));
  CHECK(n4 / n2 == Approx(4).epsilon(0.06));
}

TEST_CASE("log map on needles and obtuse triangles stays finite and exact", "[logmap][degenerate]") {
  // Relative distance error against Euclidean from three face points; the plane is where every
  // DGPC update is exact, so the fallbacks these triangles trigger must not cost accuracy here.
  const auto worstError = [](const Mesh& mesh, double radius) {
    const SurfaceGeometry geometry(mesh);
    LogMap logMap(geometry);
    double worst = 0;
    for (int f : {mesh.faceCount() / 2 + 41, mesh.faceCount() / 3, 2 * mesh.faceCount() / 3 + 5}) {
      const SurfacePoint p = SurfacePoint::inFace(mesh, f, Vec3(0.3, 0.3, 0.4));
      const auto& entries = logMap.compute(p, radius);
      requireSortedAndFinite(entries, radius);
      REQUIRE(entries.size() > 200);
      for (const LogMapEntry& e : entries) {
        const double euclid = (mesh.position(e.vertex) - p.position(mesh)).norm();
        worst = std::max(worst, std::abs(e.distance - euclid) / euclid);
      }
    }
    return worst;
  };
  const auto extremeAngles = [](const Mesh& mesh) {
    const SurfaceGeometry geometry(mesh);
    double lo = kPi, hi = 0;
    for (int h = 0; h < mesh.halfedgeCount(); ++h) {
      REQUIRE(geometry.faceNormal(Mesh::faceOf(h)).z() > 0);  // still an embedding: no folded face
      lo = std::min(lo, geometry.cornerAngle(h));
      hi = std::max(hi, geometry.cornerAngle(h));
    }
    return std::pair(lo, hi);
  };
  SECTION("very obtuse jittered grid (jitter 0.35: corners from 0.7° to 178°)") {
    const Mesh mesh = build(shapes::grid(41, 0.35, 7));
    const auto [lo, hi] = extremeAngles(mesh);
    REQUIRE(lo < 0.02);
    REQUIRE(hi > 3.1);
    CHECK(worstError(mesh, 0.3) < 1e-6);
  }
  SECTION("jittered needles (aspect 25:1)") {
    TriangleSoup soup = shapes::grid(41, 0.3, 3);
    for (Vec3& q : soup.positions) q.y() *= 0.04;
    const Mesh mesh = build(soup);
    REQUIRE(extremeAngles(mesh).first < 0.01);
    CHECK(worstError(mesh, 0.3) < 1e-6);
  }
  SECTION("folded grid (jitter 0.45 flips faces): finite, within a few % of Euclidean") {
    CHECK(worstError(build(shapes::grid(41, 0.45, 7)), 0.3) < 0.1);
  }
}

TEST_CASE("log map rejects bad input", "[logmap][errors]") {
  const Mesh mesh = build(shapes::grid(5));
  const SurfaceGeometry geometry(mesh);
  LogMap logMap(geometry);
  const SurfacePoint p = SurfacePoint::inFace(mesh, 3, Vec3::Constant(1.0 / 3));
  CHECK_THROWS_AS(logMap.compute(p, 0.0), InputError);
  CHECK_THROWS_AS(logMap.compute(p, -1.0), InputError);
  CHECK_THROWS_AS(logMap.compute(p, std::nan("")), InputError);
  CHECK_THROWS_AS(logMap.computeFromVertex(4, 0.0), InputError);
  CHECK_THROWS_AS(logMap.computeFromVertex(-1, 1.0), InputError);
  CHECK_THROWS_AS(logMap.computeFromVertex(mesh.vertexCount(), 1.0), InputError);
  SurfacePoint bad = p;
  bad.face = mesh.faceCount();
  CHECK_THROWS_WITH(logMap.compute(bad, 1.0), Catch::Contains("face " + std::to_string(mesh.faceCount())));
  bad.face = -1;
  CHECK_THROWS_AS(logMap.compute(bad, 1.0), InputError);
  bad.face = 3;
  bad.bary = Vec3(std::nan(""), 0.5, 0.5);
  CHECK_THROWS_AS(logMap.compute(bad, 1.0), InputError);
  CHECK_THROWS_AS(geoshift::logMap(mesh, bad, 1.0), InputError);
  // Still usable after a throw; an infinite radius covers the whole (connected) mesh.
  CHECK(logMap.compute(p, std::numeric_limits<double>::infinity()).size() == static_cast<size_t>(mesh.vertexCount()));
}

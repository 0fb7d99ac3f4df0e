// eval/catalogue.hpp: the holdout set's meshes and the split in four that makes them
// (docs/denoising.md#the-evaluation, "The holdout set").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>

#include "catalogue.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;
using namespace geoshift::eval;
namespace fs = std::filesystem;

namespace {

double totalArea(const Mesh& m) {
  const std::vector<double> a = faceAreas(m);
  return std::accumulate(a.begin(), a.end(), 0.0);
}

int edgeCount(const Mesh& m) {
  std::set<std::pair<int, int>> edges;
  for (const Face& f : m.faces())
    for (int k = 0; k < 3; ++k) edges.insert({std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])});
  return static_cast<int>(edges.size());
}

// A scratch folder removed when the test ends.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("geoshift-catalogue-" + std::to_string(std::rand()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

}  // namespace

TEST_CASE("splitInFour keeps the surface and adds one vertex an edge", "[eval][catalogue]") {
  SECTION("closed: an icosphere") {
    const Mesh m = buildMesh(shapes::icosphere(1)).mesh;
    const Mesh s = splitInFour(m);
    const int edges = edgeCount(m);
    CHECK(s.vertexCount() == m.vertexCount() + edges);
    CHECK(s.faceCount() == 4 * m.faceCount());
    CHECK(edgeCount(s) == 2 * edges + 3 * m.faceCount());
    CHECK(s.boundaryLoops().empty());
    // V − E + F: the sphere's 2 before and after.
    CHECK(s.vertexCount() - edgeCount(s) + s.faceCount() == 2);
    for (int v = 0; v < m.vertexCount(); ++v) CHECK(s.positions()[v] == m.positions()[v]);
    CHECK(totalArea(s) == Approx(totalArea(m)).epsilon(1e-12));
    // Every face normal is its parent's: the surface did not move.
    const std::vector<Vec3> parent = faceNormals(m), child = faceNormals(s);
    for (int f = 0; f < s.faceCount(); ++f) {
      // Children of one parent are consecutive (four per parent) or renumbered by buildMesh: find
      // the parent whose plane holds all three corners.
      bool inPlane = false;
      for (int g = 0; g < m.faceCount() && !inPlane; ++g)
        inPlane = child[f].dot(parent[g]) > 1 - 1e-12 &&
                  std::abs((s.positions()[s.faces()[f][0]] - m.positions()[m.faces()[g][0]]).dot(parent[g])) < 1e-12;
      CHECK(inPlane);
    }
  }
  SECTION("open: a grid keeps one boundary loop, twice as long") {
    const Mesh m = buildMesh(shapes::grid(6)).mesh;
    const Mesh s = splitInFour(m);
    REQUIRE(m.boundaryLoops().size() == 1);
    REQUIRE(s.boundaryLoops().size() == 1);
    CHECK(s.boundaryLoops()[0].size() == 2 * m.boundaryLoops()[0].size());
    CHECK(s.vertexCount() == m.vertexCount() + edgeCount(m));
    CHECK(totalArea(s) == Approx(totalArea(m)).epsilon(1e-12));
  }
}

TEST_CASE("loopSubdivide: Loop's rules, affine maps, convex combinations, boundaries", "[eval][catalogue]") {
  SECTION("an icosphere: the split's counts, every point inside the sphere, the rules at one vertex and edge") {
    const Mesh m = buildMesh(shapes::icosphere(1)).mesh;
    const Mesh s = loopSubdivide(m);
    CHECK(s.vertexCount() == m.vertexCount() + edgeCount(m));
    CHECK(s.faceCount() == 4 * m.faceCount());
    CHECK(s.boundaryLoops().empty());
    // Convex combinations of points on the unit sphere: inside it, and strictly (the surface shrinks).
    for (const Vec3& q : s.positions()) CHECK(q.norm() < 1 - 1e-6);
    // Vertex 0 by Loop's rule from its neighbours, computed here from the faces.
    std::set<int> nb;
    for (const Face& f : m.faces())
      for (int k = 0; k < 3; ++k)
        if (f[k] == 0) {
          nb.insert(f[(k + 1) % 3]);
          nb.insert(f[(k + 2) % 3]);
        }
    const double k = static_cast<double>(nb.size()), c = 3.0 / 8 + std::cos(2 * M_PI / k) / 4,
                 beta = (5.0 / 8 - c * c) / k;
    Vec3 expected = (1 - k * beta) * m.positions()[0];
    for (int u : nb) expected += beta * m.positions()[u];
    CHECK((s.positions()[0] - expected).norm() < 1e-12);
    // An edge point: 3/8 of its ends and 1/8 of the two opposite corners; it is one of the new
    // vertices, whatever their order.
    const Face f = m.faces()[0];
    int d = -1;
    for (const Face& g : m.faces())
      for (int j = 0; j < 3; ++j)
        if (g[j] == f[1] && g[(j + 1) % 3] == f[0]) d = g[(j + 2) % 3];
    REQUIRE(d >= 0);
    const Vec3 edgePoint = 0.375 * (m.positions()[f[0]] + m.positions()[f[1]]) +
                           0.125 * (m.positions()[f[2]] + m.positions()[d]);
    double nearest = 1e9;
    for (int v = m.vertexCount(); v < s.vertexCount(); ++v) nearest = std::min(nearest, (s.positions()[v] - edgePoint).norm());
    CHECK(nearest < 1e-12);
  }
  SECTION("commutes with an affine map") {
    const Mesh m = buildMesh(shapes::torus(12, 6)).mesh;
    Mesh moved = m;
    for (Vec3& q : moved.positions()) q = Vec3(2 * q.x() + 0.5 * q.y() + 1, -q.y() + 3, 0.25 * q.z() + q.x() - 2);
    const Mesh a = loopSubdivide(m), b = loopSubdivide(moved);
    REQUIRE(a.vertexCount() == b.vertexCount());
    for (int v = 0; v < a.vertexCount(); ++v) {
      const Vec3& q = a.positions()[v];
      CHECK((b.positions()[v] - Vec3(2 * q.x() + 0.5 * q.y() + 1, -q.y() + 3, 0.25 * q.z() + q.x() - 2)).norm() < 1e-12);
    }
  }
  SECTION("a flat grid stays flat, its boundary on its boundary's lines") {
    const Mesh m = buildMesh(shapes::grid(6)).mesh;
    const Mesh s = loopSubdivide(m);
    double zmax = 0;
    for (const Vec3& q : m.positions()) zmax = std::max(zmax, std::abs(q.z()));
    REQUIRE(zmax == 0);
    for (const Vec3& q : s.positions()) CHECK(q.z() == 0);
    REQUIRE(s.boundaryLoops().size() == 1);
    CHECK(s.boundaryLoops()[0].size() == 2 * m.boundaryLoops()[0].size());
    // The boundary curve rule keeps boundary points on the square's sides, but for the four corners,
    // which it cuts: 3/4 the corner and 1/8 each of its two boundary neighbours.
    Vec3 lo = m.positions()[0], hi = m.positions()[0];
    for (const Vec3& q : m.positions()) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const std::vector<std::vector<int>> loops = s.boundaryLoops();
    auto on = [](double a, double b) { return std::abs(a - b) < 1e-12; };
    int corners = 0;
    for (int v : loops[0]) {
      const Vec3& q = s.positions()[v];
      const bool onSide = on(q.x(), lo.x()) || on(q.x(), hi.x()) || on(q.y(), lo.y()) || on(q.y(), hi.y());
      if (v < m.vertexCount()) {
        const Vec3& c = m.positions()[v];
        if ((on(c.x(), lo.x()) || on(c.x(), hi.x())) && (on(c.y(), lo.y()) || on(c.y(), hi.y()))) {
          ++corners;
          const double h = (hi.x() - lo.x()) / 5;  // the grid's spacing: 6 vertices a side
          const Vec3 inward(on(c.x(), lo.x()) ? h : -h, on(c.y(), lo.y()) ? h : -h, 0);
          CHECK((q - (c + 0.125 * inward)).norm() < 1e-12);
          continue;
        }
      }
      CHECK(onSide);
    }
    CHECK(corners == 4);
  }
}

TEST_CASE("the holdout set: its own set, split up to its size, absent without its folder", "[eval][catalogue]") {
  SECTION("no folder: no mesh") { CHECK(holdoutMeshes("/nonexistent/geoshift-holdout").empty()); }
  SECTION("a listed file: split until it has enough vertices, and never tuning or validation") {
    TempDir dir;
    {
      // A tetrahedron as eight.off: 4 vertices, then 10, 34, 130, 514, 2050, 8194.
      std::ofstream off(dir.path / "eight.off");
      off << "OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";
    }
    std::vector<MeshEntry> meshes = holdoutMeshes(dir.path);
    REQUIRE(meshes.size() == 2);  // split in four and by Loop: one family
    CHECK(meshes[0].family == meshes[1].family);
    for (const MeshEntry& e : meshes) {
      CHECK(e.holdout);
      CHECK_FALSE(e.broad);
      CHECK_FALSE(e.seen);
      const Mesh m = e.load();
      CHECK(m.vertexCount() == 8194);
      CHECK(m.vertexCount() >= holdoutMinVertices);
    }
    const auto split = splitFamilies(meshes);
    REQUIRE(split.size() == 1);
    CHECK(split[0].second == Set::Holdout);
    CHECK(std::string(setName(Set::Holdout)) == "holdout");
  }
}

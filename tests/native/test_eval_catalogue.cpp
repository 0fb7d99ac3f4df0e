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
    REQUIRE(meshes.size() == 1);
    CHECK(meshes[0].holdout);
    CHECK_FALSE(meshes[0].broad);
    CHECK_FALSE(meshes[0].seen);
    const Mesh m = meshes[0].load();
    CHECK(m.vertexCount() == 8194);
    CHECK(m.vertexCount() >= holdoutMinVertices);
    const auto split = splitFamilies(meshes);
    REQUIRE(split.size() == 1);
    CHECK(split[0].second == Set::Holdout);
    CHECK(std::string(setName(Set::Holdout)) == "holdout");
  }
}

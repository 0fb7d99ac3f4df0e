// The finely tessellated procedural solids: the CAD-like box and the double torus.
#include <catch2/catch.hpp>

#include <set>
#include <utility>

#include "geoshift/geometry.hpp"
#include "geoshift/shapes.hpp"
#include "support.hpp"

using namespace geoshift;

namespace {

int eulerCharacteristic(const Mesh& m) {
  std::set<std::pair<int, int>> edges;
  for (const Face& f : m.faces())
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(f[k], f[(k + 1) % 3]));
  return m.vertexCount() - static_cast<int>(edges.size()) + m.faceCount();
}

// Σ (c_f · n_f A_f) / 3: the enclosed volume when every face points outward.
double signedVolume(const Mesh& m) {
  double v = 0;
  for (int f = 0; f < m.faceCount(); ++f) v += m.position(m.face(f)[0]).dot(faceCross(m, f)) / 6.0;
  return v;
}

}  // namespace

TEST_CASE("box: closed, welded, outward, exact counts and volume", "[shapes][box]") {
  const MeshBuild b = buildMesh(shapes::box(5, 4, 3, Vec3(2.0, 1.0, 0.5)));
  const Mesh& m = b.mesh;
  CHECK(b.report.clean());
  CHECK(b.report.weldedVertices == 0);  // shared edges are shared vertices already
  CHECK(m.vertexCount() == 6 * 5 * 4 - 4 * 3 * 2);
  CHECK(m.faceCount() == 4 * (5 * 4 + 4 * 3 + 3 * 5));
  CHECK(m.boundaryLoops().empty());
  CHECK(eulerCharacteristic(m) == 2);
  CHECK(signedVolume(m) == Approx(2.0 * 1.0 * 0.5));
  const Eigen::AlignedBox3d box = boundingBox(m.positions());
  CHECK((box.max() - Vec3(1.0, 0.5, 0.25)).norm() < 1e-15);
  CHECK_THAT(test::errorOf([] { shapes::box(0, 1, 1); }), Catch::Contains("box"));
}

TEST_CASE("double torus: closed genus-2 surface, outward, even triangles", "[shapes][torus]") {
  const MeshBuild b = buildMesh(shapes::doubleTorus(48));
  const Mesh& m = b.mesh;
  CHECK(b.report.clean());
  CHECK(m.boundaryLoops().empty());
  CHECK(eulerCharacteristic(m) == -2);
  CHECK(signedVolume(m) > 0);
  // The two tori (volume 2π²Rr² each) overlap a little where they merge.
  const double torusVolume = 2 * 3.14159265358979 * 3.14159265358979 * 1.0 * 0.4 * 0.4;
  CHECK(signedVolume(m) == Approx(2 * torusVolume).epsilon(0.1));
  // No slivers left from the marching: every face has an area of a sensible fraction of the mean.
  const std::vector<double> areas = faceAreas(m);
  double mean = 0, smallest = 1e300;
  for (double a : areas) {
    mean += a;
    smallest = std::min(smallest, a);
  }
  mean /= areas.size();
  INFO("smallest face area / mean " << smallest / mean << ", " << m.vertexCount() << " vertices");
  CHECK(smallest > 0.02 * mean);
  CHECK_THAT(test::errorOf([] { shapes::doubleTorus(3); }), Catch::Contains("resolution"));
}

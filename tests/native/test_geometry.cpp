// Lengths, normals, areas and bounds on procedural meshes.
#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>

#include "geoshift/geometry.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// Σ (a · (b × c)) / 6 over the faces: positive iff the closed surface is oriented outward.
double signedVolume(const Mesh& m) {
  double vol = 0;
  for (const Face& f : m.faces()) {
    vol += m.position(f[0]).dot(m.position(f[1]).cross(m.position(f[2]))) / 6.0;
  }
  return vol;
}

}  // namespace

TEST_CASE("mixed Voronoi areas sum to the total area", "[geometry][area]") {
  SECTION("icosphere (all acute)") {
    const Mesh m = build(shapes::icosphere(3));
    CHECK(sum(mixedVoronoiAreas(m)) == Approx(sum(faceAreas(m))).epsilon(1e-12));
  }
  SECTION("jittered grid with obtuse triangles") {
    const Mesh m = build(shapes::grid(25, 0.3, 7));
    int obtuse = 0;
    for (const Face& f : m.faces()) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = m.position(f[k]);
        if ((m.position(f[(k + 1) % 3]) - p).dot(m.position(f[(k + 2) % 3]) - p) < 0) ++obtuse;
      }
    }
    REQUIRE(obtuse > 20);  // the obtuse branch is really exercised
    for (const Vec3& n : faceNormals(m)) REQUIRE(n.z() > 0);  // and no triangle folded over
    const double total = sum(faceAreas(m));
    CHECK(total == Approx(1.0).epsilon(1e-12));  // jitter moves interior vertices only
    CHECK(sum(mixedVoronoiAreas(m)) == Approx(total).epsilon(1e-12));
    for (double a : mixedVoronoiAreas(m)) CHECK(a > 0);
  }
}

TEST_CASE("average edge length of the unit grid", "[geometry][ael]") {
  const int n = 11;
  const double h = 1.0 / (n - 1);
  // n(n-1) edges along x and as many along y, all of length h; (n-1)² diagonals of length h√2.
  const double axis = 2.0 * n * (n - 1), diagonal = (n - 1) * (n - 1);
  const double expected = (axis * h + diagonal * h * std::sqrt(2.0)) / (axis + diagonal);
  CHECK(averageEdgeLength(build(shapes::grid(n))) == Approx(expected).epsilon(1e-14));
}

TEST_CASE("normals point outward on the icosphere", "[geometry][normals]") {
  const double radius = 2.5;
  const Mesh m = build(shapes::icosphere(3, radius));
  const std::vector<Vec3> fn = faceNormals(m);
  for (int f = 0; f < m.faceCount(); ++f) {
    const Face& t = m.face(f);
    const Vec3 centroid = (m.position(t[0]) + m.position(t[1]) + m.position(t[2])) / 3.0;
    CHECK(fn[f].dot(centroid) > 0);
    CHECK(fn[f].norm() == Approx(1.0).epsilon(1e-12));
  }
  const std::vector<Vec3> vn = vertexNormals(m);
  double worst = 1;
  for (int v = 0; v < m.vertexCount(); ++v) {
    CHECK(vn[v].norm() == Approx(1.0).epsilon(1e-12));
    worst = std::min(worst, vn[v].dot(m.position(v) / radius));
  }
  CHECK(worst > 0.999);  // on a sphere the vertex normal is nearly the radial direction
}

TEST_CASE("vertex normals are weighted by corner angle, not area", "[geometry][normals]") {
  // Vertex 0 sits on a 90° fold: two faces in z = 0 and three large faces in x = 0. Area weights
  // would tilt the normal toward the large faces; the expected value is the angle-weighted sum.
  std::vector<Vec3> p = {Vec3(0, 0, 0), Vec3(0, 1, 0),  Vec3(-1, 0, 0), Vec3(0, -1, 0),
                         Vec3(0, 0, -1), Vec3(0, 5, -5)};
  const Mesh m(p, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1}});
  Vec3 byAngle = Vec3::Zero(), byArea = Vec3::Zero();
  for (const Face& f : m.faces()) {
    const Vec3 a = m.position(f[1]) - m.position(f[0]), b = m.position(f[2]) - m.position(f[0]);
    byAngle += std::acos(a.normalized().dot(b.normalized())) * a.cross(b).normalized();
    byArea += a.cross(b);
  }
  const Vec3 n = vertexNormals(m)[0];
  CHECK((n - byAngle.normalized()).norm() < 1e-12);
  CHECK((n - byArea.normalized()).norm() > 0.1);
}

TEST_CASE("isolated vertices get a zero normal", "[geometry][normals]") {
  const Mesh m({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 5, 5)}, {{0, 1, 2}});
  const auto vn = vertexNormals(m);
  CHECK(vn[3].isZero(0));
  CHECK((vn[0] - Vec3(0, 0, 1)).norm() < 1e-15);
  CHECK(mixedVoronoiAreas(m)[3] == 0.0);
}

TEST_CASE("procedural shapes are closed and outward where they should be", "[geometry][shapes]") {
  CHECK(signedVolume(build(shapes::tetrahedron())) > 0);
  CHECK(signedVolume(build(shapes::cube())) == Approx(8.0).epsilon(1e-14));
  const Mesh sphere = build(shapes::icosphere(4));
  CHECK(sphere.vertexCount() == 10 * 256 + 2);
  CHECK(sphere.boundaryLoops().empty());
  CHECK(signedVolume(sphere) == Approx(4.0 / 3.0 * M_PI).epsilon(5e-3));
  const Mesh torus = build(shapes::torus(64, 32, 1.0, 0.35));
  CHECK(torus.boundaryLoops().empty());
  CHECK(signedVolume(torus) == Approx(2 * M_PI * M_PI * 0.35 * 0.35).epsilon(1e-2));
  // The cylinder is open: its vertex normals point away from the axis.
  const Mesh cyl = build(shapes::cylinder(32, 4));
  CHECK(cyl.boundaryLoops().size() == 2);
  const auto vn = vertexNormals(cyl);
  for (int v = 0; v < cyl.vertexCount(); ++v) {
    CHECK(vn[v].dot(Vec3(cyl.position(v).x(), cyl.position(v).y(), 0)) > 0.9);
  }
  // Unwelded then welded back gives the same mesh size.
  const MeshBuild rebuilt = buildMesh(shapes::unwelded(shapes::icosphere(2)));
  CHECK(rebuilt.mesh.vertexCount() == 162);
  CHECK(rebuilt.mesh.boundaryLoops().empty());
}

TEST_CASE("unit cube transform maps the box to longest side 1, centred", "[geometry][bbox]") {
  Mesh m = build(shapes::torus(24, 12, 3.0, 1.0));
  for (Vec3& p : m.positions()) p = 0.5 * p + Vec3(10, -4, 7);
  const Eigen::AlignedBox3d before = boundingBox(m.positions());
  const Similarity s = normalizeToUnitCube(m);
  const Eigen::AlignedBox3d box = boundingBox(m.positions());
  CHECK(s.scale == Approx(1.0 / before.sizes().maxCoeff()));
  CHECK(box.sizes().maxCoeff() == Approx(1.0).epsilon(1e-14));
  CHECK((box.center() - Vec3::Constant(0.5)).norm() < 1e-14);
  CHECK(box.min().minCoeff() >= -1e-14);
  CHECK(box.max().maxCoeff() <= 1 + 1e-14);
  CHECK(boundingBox({}).isEmpty());
}

TEST_CASE("meanNormalTurn is the normals' mean angle across interior edges", "[geometry][normals]") {
  // The cube's 12 edges turn by a right angle and its 6 face diagonals not at all.
  const Mesh cube = build(shapes::cube());
  CHECK(meanNormalTurn(cube, cube.positions()) == Approx(M_PI / 3).epsilon(1e-14));
  // Every edge of the icosahedron turns by π minus its dihedral angle, acos(√5 / 3).
  const Mesh ico = build(shapes::icosphere(0));
  REQUIRE(ico.vertexCount() == 12);
  CHECK(meanNormalTurn(ico, ico.positions()) == Approx(std::acos(std::sqrt(5.0) / 3)).epsilon(1e-12));
  // The positions given, not the mesh's: a scaled copy turns the same, a flat grid not at all (its
  // boundary edges do not count), and folding the grid's half up by θ adds θ on the fold's edges.
  std::vector<Vec3> scaled = ico.positions();
  for (Vec3& p : scaled) p *= 7;
  CHECK(meanNormalTurn(ico, scaled) == Approx(std::acos(std::sqrt(5.0) / 3)).epsilon(1e-12));
  const Mesh grid = build(shapes::grid(9));
  CHECK(meanNormalTurn(grid, grid.positions()) == 0.0);
  const double theta = 0.4;
  std::vector<Vec3> folded = grid.positions();
  for (Vec3& p : folded)
    if (p.x() > 0.5) p = Vec3(0.5 + (p.x() - 0.5) * std::cos(theta), p.y(), (p.x() - 0.5) * std::sin(theta));
  // 9 × 9 vertices: 208 edges, 32 on the boundary; the fold runs along 8 of the 176 interior ones.
  CHECK(meanNormalTurn(grid, folded) == Approx(8 * theta / 176).epsilon(1e-12));
  // Noise adds to it.
  const Mesh sphere = build(shapes::icosphere(3));
  std::vector<Vec3> noisy = sphere.positions();
  for (size_t v = 0; v < noisy.size(); ++v) noisy[v] *= 1 + 0.03 * std::sin(12.9898 * v);
  CHECK(meanNormalTurn(sphere, noisy) > 1.5 * meanNormalTurn(sphere, sphere.positions()));
  CHECK_THROWS_WITH(meanNormalTurn(sphere, grid.positions()), Catch::Contains("positions for a mesh of"));
}

// Vertex update from target face normals (docs/algorithms.md#vertex-update) and face normals from vertex normals.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <random>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/vertex_update.hpp"
#include "support.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

Mesh noisy(const TriangleSoup& soup, double amount, std::uint64_t seed = 3) {
  Mesh m = build(soup);
  NoiseOptions o;
  o.amount = amount;
  o.seed = seed;
  addNoise(m, o);
  return m;
}

// Faces whose normal turned by 90° or more between `before` and `after` (same connectivity).
int flippedFaces(const Mesh& before, const std::vector<Vec3>& after) {
  int count = 0;
  for (int f = 0; f < before.faceCount(); ++f) {
    const Face& t = before.face(f);
    const Vec3 n = (after[t[1]] - after[t[0]]).cross(after[t[2]] - after[t[0]]);
    if (n.dot(faceCross(before, f)) <= 0) ++count;
  }
  return count;
}

double maxMove(const Mesh& m, const std::vector<Vec3>& x) {
  double d = 0;
  for (int v = 0; v < m.vertexCount(); ++v) d = std::max(d, (x[v] - m.position(v)).norm());
  return d;
}

}  // namespace

TEST_CASE("vertex update with the current face normals is a no-op", "[vertex_update]") {
  const bool area = GENERATE(false, true);
  for (const Mesh& m : {noisy(shapes::icosphere(3), 0.4), noisy(shapes::box(6, 5, 4), 0.3),
                        noisy(shapes::grid(9, 0.3), 0.2)}) {
    VertexUpdateOptions o;
    o.areaWeighted = area;
    const VertexUpdateResult r = updateVertices(m, faceNormals(m), o);
    CHECK(r.iterations == 20);
    CHECK(maxMove(m, r.positions) <= 1e-12);
    CHECK(r.maxDisplacement <= 1e-12);
  }
}

TEST_CASE("vertex update flattens a noisy plane along the target normal only", "[vertex_update]") {
  const bool area = GENERATE(false, true);
  TriangleSoup soup = shapes::grid(15, 0.3);
  std::mt19937 rng(5);
  for (Vec3& p : soup.positions) p.z() = 0.02 * (static_cast<double>(rng()) / 4294967296.0 - 0.5);
  const Mesh m = build(soup);
  VertexUpdateOptions o;
  o.iterations = 1000;
  o.areaWeighted = area;
  const VertexUpdateResult r =
      updateVertices(m, std::vector<Vec3>(m.faceCount(), Vec3(0, 0, 2)), o);  // not unit: normalised
  double zMin = 1, zMax = -1;
  for (int v = 0; v < m.vertexCount(); ++v) {
    // Every pull is along n' = z, so x and y cannot change.
    CHECK(r.positions[v].x() == m.position(v).x());
    CHECK(r.positions[v].y() == m.position(v).y());
    zMin = std::min(zMin, r.positions[v].z());
    zMax = std::max(zMax, r.positions[v].z());
  }
  INFO("z spread after: " << zMax - zMin);
  CHECK(zMax - zMin < 1e-3 * 0.02);
}

TEST_CASE("vertex update pulls a noisy sphere towards its exact normals without flips", "[vertex_update][flip]") {
  const double amount = GENERATE(0.5, 1.0);
  const FlipGuard guard = GENERATE(FlipGuard::Input, FlipGuard::InputOrTarget);
  const Mesh clean = build(shapes::icosphere(4));
  Mesh m = clean;
  NoiseOptions no;
  no.amount = amount;
  addNoise(m, no);
  // The exact normals of the clean sphere's faces (radial through the clean centroids).
  std::vector<Vec3> target(m.faceCount());
  for (int f = 0; f < m.faceCount(); ++f) {
    const Face& t = clean.face(f);
    target[f] = (clean.position(t[0]) + clean.position(t[1]) + clean.position(t[2])).normalized();
  }
  VertexUpdateOptions o;
  o.iterations = 50;
  o.flipGuard = guard;
  const VertexUpdateResult r = updateVertices(m, target, o);
  auto angleError = [&](const std::vector<Vec3>& x) {
    double s = 0;
    for (int f = 0; f < m.faceCount(); ++f) {
      const Face& t = m.face(f);
      const Vec3 n = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).normalized();
      s += std::acos(std::clamp(n.dot(target[f]), -1.0, 1.0));
    }
    return s / m.faceCount();
  };
  int wrongSide = 0;  // faces against both their input and their target normal
  for (int f = 0; f < m.faceCount(); ++f) {
    const Face& t = m.face(f);
    const Vec3 n = (r.positions[t[1]] - r.positions[t[0]]).cross(r.positions[t[2]] - r.positions[t[0]]);
    wrongSide += n.dot(faceCross(m, f)) <= 0 && n.dot(target[f]) <= 0;
  }
  INFO("noise " << amount << " AEL, guard " << static_cast<int>(guard) << ": limited " << r.limitedSteps
                << ", frozen " << r.frozenSteps << "; angle error " << angleError(m.positions()) << " -> "
                << angleError(r.positions));
  if (guard == FlipGuard::Input) CHECK(flippedFaces(m, r.positions) == 0);
  CHECK(wrongSide == 0);
  // Unfolding what the noise folded is what InputOrTarget allows beyond Input.
  CHECK(angleError(r.positions) < (amount < 0.75 ? 0.5 : 0.8) * angleError(m.positions()));
}

TEST_CASE("the flip guard holds against adversarial targets", "[vertex_update][flip]") {
  const Mesh m = noisy(shapes::icosphere(3), 0.5);
  std::vector<Vec3> target = faceNormals(m);
  SECTION("targets tangent to the surface") {
    for (Vec3& n : target) n = n.cross(Vec3(0.3, 0.5, 0.8));
  }
  SECTION("random targets") {
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    for (Vec3& n : target) n = Vec3(g(rng), g(rng), g(rng));
  }
  const VertexUpdateResult r = updateVertices(m, target, {30});
  INFO("limited " << r.limitedSteps << ", frozen " << r.frozenSteps);
  CHECK(r.limitedSteps > 0);  // the guard had work to do
  CHECK(flippedFaces(m, r.positions) == 0);
}

TEST_CASE("k iterations are one iteration k times: what an iteration hands the next is not stale", "[vertex_update][flip]") {
  // An iteration hands the next its faces' planes and cross products, computed at the candidates the
  // guard accepted; a fresh call computes them from its positions. Random targets make the guard
  // halve and freeze many steps, so faces are checked again within an iteration.
  const FlipGuard guard = GENERATE(FlipGuard::Input, FlipGuard::InputOrTarget);
  const Mesh m = noisy(shapes::icosphere(3), 0.5);
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  std::vector<Vec3> target(m.faceCount());
  for (Vec3& n : target) n = Vec3(g(rng), g(rng), g(rng));
  VertexUpdateOptions o;
  o.iterations = 6;
  o.flipGuard = guard;
  o.referenceNormals = referenceNormalsOf(m);
  const VertexUpdateResult all = updateVertices(m, target, o);
  INFO("limited " << all.limitedSteps << ", frozen " << all.frozenSteps);
  REQUIRE(all.limitedSteps > 100);
  REQUIRE(all.frozenSteps > 0);
  Mesh stepwise = m;
  VertexUpdateOptions one = o;
  one.iterations = 1;
  int limited = 0, frozen = 0;
  for (int k = 0; k < o.iterations; ++k) {
    const VertexUpdateResult r = updateVertices(stepwise, target, one);
    stepwise.positions() = r.positions;
    limited += r.limitedSteps;
    frozen += r.frozenSteps;
  }
  CHECK(stepwise.positions() == all.positions);  // to the bit
  CHECK(limited == all.limitedSteps);
  CHECK(frozen == all.frozenSteps);
}

TEST_CASE("fixed boundary keeps the border vertices in place", "[vertex_update][boundary]") {
  const Mesh m = noisy(shapes::grid(12), 0.3);
  VertexUpdateOptions o;
  o.fixedBoundary = true;
  const VertexUpdateResult r = updateVertices(m, std::vector<Vec3>(m.faceCount(), Vec3(0, 0, 1)), o);
  int moved = 0;
  for (int v = 0; v < m.vertexCount(); ++v) {
    if (m.isBoundaryVertex(v)) CHECK(r.positions[v] == m.position(v));
    else moved += r.positions[v] != m.position(v);
  }
  CHECK(moved > 0);
}

TEST_CASE("one iteration is the mean pull of a vertex's faces, faces without a target left out", "[vertex_update]") {
  // Brute force over all faces in index order against the update's per-vertex lists: an open grid
  // (boundary vertices and their fans), a few faces with no target, with and without area weights.
  const bool area = GENERATE(false, true);
  const Mesh m = noisy(shapes::grid(10, 0.3), 0.15);
  std::vector<Vec3> target = faceNormals(m);
  for (Vec3& n : target) n = (n + Vec3(0.05, -0.03, 0.0)).normalized();
  // No target for a few faces and for every face around one interior vertex, which then stays.
  const int bare = 55;
  REQUIRE(!m.isBoundaryVertex(bare));
  m.forEachOutgoing(bare, [&](int h) { target[Mesh::faceOf(h)] = Vec3::Zero(); });
  for (int f : {0, 7, 90}) target[f] = Vec3::Zero();
  VertexUpdateOptions o;
  o.iterations = 1;
  o.areaWeighted = area;
  const VertexUpdateResult r = updateVertices(m, target, o);
  REQUIRE(r.limitedSteps == 0);  // no step shortened: the plain formula applies everywhere
  std::vector<Vec3> sum(m.vertexCount(), Vec3::Zero());
  std::vector<double> wsum(m.vertexCount(), 0.0);
  for (int f = 0; f < m.faceCount(); ++f) {
    if (target[f] == Vec3::Zero()) continue;
    const Face& t = m.face(f);
    const Vec3 c = (m.position(t[0]) + m.position(t[1]) + m.position(t[2])) / 3;
    const double w = area ? 0.5 * faceCross(m, f).norm() : 1.0;
    for (int v : t) {
      sum[v] += w * target[f].dot(c - m.position(v)) * target[f];
      wsum[v] += w;
    }
  }
  for (int v = 0; v < m.vertexCount(); ++v) {
    const Vec3 expected = wsum[v] > 0 ? Vec3(m.position(v) + sum[v] / wsum[v]) : m.position(v);
    INFO("vertex " << v);
    CHECK((r.positions[v] - expected).norm() <= 1e-12);
  }
  CHECK(wsum[bare] == 0);
  CHECK(r.positions[bare] == m.position(bare));
  CHECK(r.maxDisplacement > 0);
}

TEST_CASE("vertex update rejects bad input and honours cancel", "[vertex_update][input]") {
  const Mesh m = build(shapes::icosphere(2));
  std::vector<Vec3> n = faceNormals(m);
  CHECK_THAT(test::errorOf([&] { updateVertices(m, std::vector<Vec3>(3, Vec3(0, 0, 1))); }),
             Catch::Contains("3 target normals for 320 faces"));
  n[17] = Vec3(0, NAN, 1);
  CHECK_THAT(test::errorOf([&] { updateVertices(m, n); }), Catch::Contains("face 17"));
  n[17] = Vec3(0, 0, 1);
  CHECK_THAT(test::errorOf([&] { updateVertices(m, n, {-1}); }), Catch::Contains("iterations"));

  std::atomic<bool> cancel{true};
  Progress p;
  p.cancel = &cancel;
  CHECK_THROWS_AS(updateVertices(m, n, {}, p), Cancelled);
  int reports = 0;
  Progress counting;
  counting.report = [&](double, std::string_view stage) {
    CHECK(stage == "vertex update");
    ++reports;
  };
  updateVertices(m, n, {5}, counting);
  CHECK(reports == 6);
}

TEST_CASE("face normals from vertex normals: normalised mean of the corners", "[vertex_update][normals]") {
  const Mesh m = build(shapes::icosphere(3));
  std::vector<Vec3> radial(m.positions());  // unit sphere: position = exact normal
  const std::vector<Vec3> fn = faceNormalsFromVertexNormals(m, radial);
  for (int f = 0; f < m.faceCount(); ++f) {
    const Face& t = m.face(f);
    const Vec3 expected = (radial[t[0]] + radial[t[1]] + radial[t[2]]).normalized();
    CHECK((fn[f] - expected).norm() < 1e-14);
    CHECK(fn[f].dot(faceNormals(m)[f]) > 0.99);
  }
  // Lengths do not weigh: one long corner normal does not dominate.
  std::vector<Vec3> scaled(m.vertexCount(), Vec3(0, 0, 1));
  scaled[m.face(0)[0]] = Vec3(1000, 0, 0);
  CHECK((faceNormalsFromVertexNormals(m, scaled)[0] - Vec3(1, 0, 2).normalized()).norm() < 1e-14);
  // Corner normals that cancel fall back to the face's own normal.
  std::vector<Vec3> zero(m.vertexCount(), Vec3::Zero());
  CHECK((faceNormalsFromVertexNormals(m, zero)[5] - faceNormals(m)[5]).norm() < 1e-14);

  CHECK_THAT(test::errorOf([&] { faceNormalsFromVertexNormals(m, std::vector<Vec3>(2)); }),
             Catch::Contains("2 vertex normals for 642 vertices"));
  radial[9] = Vec3(INFINITY, 0, 0);
  CHECK_THAT(test::errorOf([&] { faceNormalsFromVertexNormals(m, radial); }), Catch::Contains("vertex 9"));
}

TEST_CASE("vertex update gives the same result on any number of threads", "[vertex_update][threads]") {
  // Tangent targets keep the flip guard busy, so the halving rounds run too.
  const Mesh m = noisy(shapes::icosphere(4), 0.5);
  std::vector<Vec3> target = faceNormals(m);
  for (Vec3& n : target) n = (n + 0.8 * n.cross(Vec3(0.3, 0.5, 0.8))).eval();
  VertexUpdateOptions o;
  o.iterations = 12;
  o.parallel.threads = 1;
  const VertexUpdateResult serial = updateVertices(m, target, o);
  REQUIRE(serial.limitedSteps > 0);
  double farthest = 0;  // brute force
  for (int v = 0; v < m.vertexCount(); ++v) farthest = std::max(farthest, (serial.positions[v] - m.position(v)).norm());
  CHECK(serial.maxDisplacement == farthest);
  CHECK(farthest > 0);
  for (int threads : {2, 3, 4}) {
    o.parallel.threads = threads;
    const VertexUpdateResult r = updateVertices(m, target, o);
    INFO(threads << " threads");
    CHECK(r.positions == serial.positions);
    CHECK(r.limitedSteps == serial.limitedSteps);
    CHECK(r.frozenSteps == serial.frozenSteps);
    CHECK(r.maxDisplacement == serial.maxDisplacement);
  }
  // Several bad targets: the error names the first, whichever thread saw one.
  target[900] = Vec3(INFINITY, 0, 1);
  target[17] = Vec3(0, NAN, 1);
  o.parallel.threads = 4;
  CHECK_THAT(test::errorOf([&] { updateVertices(m, target, o); }), Catch::Contains("face 17 "));
}

TEST_CASE("a plan made once gives what the lists built per call give", "[vertex_update][plan]") {
  // An open grid (a boundary, with and without fixed boundary) and a closed sphere, with tangent
  // targets that keep the flip guard busy; then a face without a target, where the plan must be
  // set aside (it lists every face), and plans for another mesh or boundary rule, refused.
  const bool fixed = GENERATE(false, true);
  for (const Mesh& m : {noisy(shapes::grid(14, 0.3), 0.4), noisy(shapes::icosphere(3), 0.5)}) {
    std::vector<Vec3> target = faceNormals(m);
    for (Vec3& n : target) n = (n + 0.6 * n.cross(Vec3(0.3, 0.5, 0.8))).eval();
    VertexUpdateOptions o;
    o.iterations = 8;
    o.fixedBoundary = fixed;
    o.flipGuard = FlipGuard::InputOrTarget;
    const VertexUpdatePlan plan = planVertexUpdate(m, o);
    CHECK(plan.firstFace.back() == static_cast<int>(plan.gatherFace.size()));
    const VertexUpdateResult own = updateVertices(m, target, o);
    REQUIRE(own.limitedSteps > 0);
    o.plan = &plan;
    for (int threads : {1, 3}) {
      o.parallel.threads = threads;
      const VertexUpdateResult planned = updateVertices(m, target, o);
      INFO(threads << " threads, fixed boundary " << fixed);
      CHECK(planned.positions == own.positions);
      CHECK(planned.limitedSteps == own.limitedSteps);
    }
    // A face without a target: the plan would let it weigh in the vertices' means.
    target[5] = Vec3::Zero();
    o.plan = nullptr;
    const VertexUpdateResult ownBare = updateVertices(m, target, o);
    o.plan = &plan;
    CHECK(updateVertices(m, target, o).positions == ownBare.positions);
    CHECK(ownBare.positions != own.positions);
    // Made for the other boundary rule, or for another mesh.
    VertexUpdateOptions other = o;
    other.fixedBoundary = !fixed;
    CHECK_THAT(test::errorOf([&] { updateVertices(m, target, other); }), Catch::Contains("the plan was made for"));
    const Mesh small = build(shapes::icosphere(1));
    other = o;
    CHECK_THAT(test::errorOf([&] { updateVertices(small, faceNormals(small), other); }),
               Catch::Contains("not for this mesh (42 vertices, 80 faces)"));
  }
}

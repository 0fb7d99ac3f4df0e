// Bilateral normal filtering (Zheng et al. 2011) as a denoiser: noise goes, sharp edges stay.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <utility>

#include "geoshift/bilateral_normal.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "denoise_support.hpp"
#include "support.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

}  // namespace

// Fixed 0.3 AEL and the uniform reading of the paper's noise, |d| in [0, 0.5 AEL]. At a fixed 0.5 AEL
// Zheng et al.'s defaults lose the edges (mean dihedral error about 17°): see the evaluation table.
TEST_CASE("bilateral normal filtering denoises a CAD block and keeps its edges", "[bilateral][features]") {
  const auto [amount, distribution] = GENERATE(std::make_pair(0.3, NoiseDistribution::Fixed),
                                               std::make_pair(0.5, NoiseDistribution::Uniform));
  const Mesh clean = build(shapes::box(20, 14, 10, Vec3(1.0, 0.7, 0.5)));
  Mesh m = withNoise(clean, amount, 1, distribution);
  const double noisy = rmsTo(m, clean);
  const double noisyEdges = [&] {
    auto e = featureEdgeErrors(clean, m);
    double s = 0;
    for (double x : e) s += x;
    return s / e.size();
  }();
  const Mesh input = m;
  const BilateralNormalResult r = bilateralNormalDenoise(m);
  int flipped = 0;
  for (int f = 0; f < m.faceCount(); ++f) flipped += faceCross(m, f).dot(faceCross(input, f)) <= 0;
  CHECK(flipped == 0);
  const std::vector<double> errors = featureEdgeErrors(clean, m);
  REQUIRE(errors.size() == 4u * (20 + 14 + 10));  // every box edge segment, nothing else
  double mean = 0;
  for (double x : errors) mean += x;
  mean /= errors.size();
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  INFO("noise " << amount << " AEL " << (distribution == NoiseDistribution::Fixed ? "fixed" : "uniform") << ": RMS " << noisy << " -> " << rmsTo(m, clean) << "; feature dihedral error "
                << noisyEdges << "° -> mean " << mean << "°, median " << sorted[sorted.size() / 2]
                << "°, 90th percentile " << sorted[sorted.size() * 9 / 10] << "°; sigma_c " << r.sigmaSpatial);
  CHECK(rmsTo(m, clean) < 0.5 * noisy);
  CHECK(mean < 10.0);
  CHECK(sorted[sorted.size() * 9 / 10] < 10.0);
  CHECK(meanNormalAngleError(m, clean) < 0.5 * meanNormalAngleError(withNoise(clean, amount, 1, distribution), clean));
}

TEST_CASE("bilateral normal filtering denoises a sphere", "[bilateral][sphere]") {
  const auto neighborhood = GENERATE(FaceNeighborhood::Vertex, FaceNeighborhood::Edge);
  const Mesh clean = build(shapes::icosphere(4));
  Mesh m = withNoise(clean, 0.5, 4);
  const double noisy = rmsTo(m, clean);
  BilateralNormalOptions o;
  o.neighborhood = neighborhood;
  const BilateralNormalResult r = bilateralNormalDenoise(m, o);
  INFO("RMS " << noisy << " -> " << rmsTo(m, clean));
  CHECK(rmsTo(m, clean) < 0.5 * noisy);
  // The mean distance between adjacent centroids of a near-regular mesh is about AEL / sqrt(3).
  CHECK(r.sigmaSpatial == Approx(averageEdgeLength(withNoise(clean, 0.5, 4)) / std::sqrt(3.0)).epsilon(0.2));
  CHECK(r.vertexUpdate.iterations == 10);
}

TEST_CASE("zero normal iterations leave a mesh as it is", "[bilateral]") {
  Mesh m = withNoise(build(shapes::icosphere(3)), 0.5);
  const std::vector<Vec3> before = m.positions();
  BilateralNormalOptions o;
  o.normalIterations = 0;
  bilateralNormalDenoise(m, o);
  for (int v = 0; v < m.vertexCount(); ++v) CHECK((m.position(v) - before[v]).norm() <= 1e-12);
}

TEST_CASE("a spatial sigma in AEL units is used as given", "[bilateral]") {
  Mesh m = build(shapes::grid(8));
  BilateralNormalOptions o;
  o.sigmaSpatial = 2.0;
  CHECK(bilateralNormalDenoise(m, o).sigmaSpatial == Approx(2.0 * averageEdgeLength(m)));
}

TEST_CASE("bilateral normal filtering rejects bad options and honours cancel", "[bilateral][input]") {
  Mesh m = withNoise(build(shapes::icosphere(3)), 0.5);
  const std::vector<Vec3> before = m.positions();
  BilateralNormalOptions o;
  o.sigmaRange = 0;
  CHECK_THAT(test::errorOf([&] { bilateralNormalDenoise(m, o); }), Catch::Contains("range sigma"));
  o = {};
  o.sigmaSpatial = -1;
  CHECK_THAT(test::errorOf([&] { bilateralNormalDenoise(m, o); }), Catch::Contains("spatial sigma"));
  o = {};
  o.normalIterations = -2;
  CHECK_THAT(test::errorOf([&] { bilateralNormalDenoise(m, o); }), Catch::Contains("normal iterations"));
  CHECK_THAT(test::errorOf([&] { bilateralFilterFaceNormals(m, {}, 1.0, {}); }),
             Catch::Contains("0 normals for 1280 faces"));

  // Cancel in the middle of the vertex update: the mesh must come back untouched.
  std::atomic<bool> cancel{false};
  Progress p;
  p.cancel = &cancel;
  p.report = [&](double fraction, std::string_view stage) {
    if (stage == "vertex update" && fraction > 0.4) cancel = true;
  };
  CHECK_THROWS_AS(bilateralNormalDenoise(m, {}, p), Cancelled);
  CHECK(m.positions() == before);
}

// Denoising by Riemannian mean shift on vertex normals (the paper's §4.1): noise goes, edges stay,
// no face flips, both range updates run, cancel leaves the mesh as it was.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <numeric>

#include "geoshift/denoise.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "denoise_support.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

}  // namespace

// The uniform reading of the paper's noise, |d| in [0, 0.5 AEL], on a 12×12×12 block. The default
// lands at about 6° of feature dihedral error (21° noisy); the paper's face-normal rule
// (FaceNormalRule::Mean) bevels the edges to about 46°.
TEST_CASE("denoising a noisy CAD block halves the error and sharpens its edges", "[denoise]") {
  const Mesh clean = build(shapes::box(12, 12, 12));
  const Mesh noisy = withNoise(clean, 0.5, 3, NoiseDistribution::Uniform);
  const double noisyRms = rmsTo(noisy, clean), noisyEdges = meanFeatureEdgeError(clean, noisy);
  for (RangeUpdate update : {RangeUpdate::Sampled, RangeUpdate::Joint}) {
    Mesh m = noisy;
    DenoiseOptions o;
    o.meanShift.rangeUpdate = update;
    const DenoiseResult r = denoise(m, o);
    const double after = rmsTo(m, clean), edges = meanFeatureEdgeError(clean, m);
    INFO((update == RangeUpdate::Joint ? "joint" : "sampled") << ": RMS " << noisyRms << " -> " << after
                                                                   << ", feature dihedral error " << noisyEdges << " -> "
                                                                   << edges << "°, " << r.meanIterations << " iterations");
    REQUIRE(after < 0.5 * noisyRms);
    REQUIRE(edges < noisyEdges);
    if (update == RangeUpdate::Sampled) REQUIRE(edges < 10);  // the default
    REQUIRE(flippedFaces(noisy, m) == 0);  // never, across all passes
    REQUIRE(flippedFaces(clean, m) <= m.faceCount() / 200);  // faces the noise folded may stay folded
    REQUIRE(r.convergedFraction > 0.9);
  }
  // The paper's face-normal rule bevels: the consensus rule is what keeps the edges.
  Mesh paper = noisy;
  DenoiseOptions o;
  o.faceNormals = FaceNormalRule::Mean;
  denoise(paper, o);
  REQUIRE(meanFeatureEdgeError(clean, paper) > 30);
}

TEST_CASE("denoising a noisy sphere halves the error", "[denoise]") {
  const Mesh clean = build(shapes::icosphere(4));
  const Mesh noisy = withNoise(clean, 0.5, 5, NoiseDistribution::Uniform);
  Mesh m = noisy;
  denoise(m);
  INFO("RMS " << rmsTo(noisy, clean) << " -> " << rmsTo(m, clean));
  REQUIRE(rmsTo(m, clean) < 0.5 * rmsTo(noisy, clean));
  REQUIRE(flippedFaces(noisy, m) == 0);
}

TEST_CASE("hybrid denoising: the coarse mesh is denoised, the details dropped", "[denoise][hybrid]") {
  const Mesh clean = build(shapes::icosphere(5));
  const Mesh noisy = withNoise(clean, 0.5, 8, NoiseDistribution::Uniform);
  Mesh m = noisy;
  DenoiseOptions o;
  o.levels = 2;
  o.alpha = {0};
  const DenoiseResult r = denoise(m, o);
  INFO("RMS " << rmsTo(noisy, clean) << " -> " << rmsTo(m, clean) << " filtering " << r.filteredVertices << " vertices");
  REQUIRE(m.vertexCount() == clean.vertexCount());
  REQUIRE(r.filteredVertices < 0.65 * clean.vertexCount());
  REQUIRE(rmsTo(m, clean) < 0.5 * rmsTo(noisy, clean));
  o.levels = 2;
  o.alpha = {0, 0, 0};  // three gains for two levels
  REQUIRE_THROWS_AS(denoise(m, o), InputError);
}

TEST_CASE("denoising a clean plane leaves it planar", "[denoise]") {
  Mesh m = build(shapes::grid(20, 0.3));
  denoise(m);
  for (const Vec3& p : m.positions()) REQUIRE(std::abs(p.z()) < 1e-9);
}

TEST_CASE("denoise rejects bad options and cancels without touching the mesh", "[denoise]") {
  Mesh m = withNoise(build(shapes::icosphere(3)), 0.3, 3);
  const std::vector<Vec3> before = m.positions();
  DenoiseOptions bad;
  bad.passes = 0;
  REQUIRE_THROWS_AS(denoise(m, bad), InputError);
  bad = {};
  bad.meanShift.spatialBandwidth = 0;
  REQUIRE_THROWS_AS(denoise(m, bad), InputError);
  REQUIRE(m.positions() == before);

  std::atomic<bool> cancel{false};
  Progress progress;
  progress.cancel = &cancel;
  int reports = 0;
  // Cancel in the second pass, after a vertex update has moved the mesh once.
  progress.report = [&](double f, std::string_view) {
    ++reports;
    if (f > 0.5) cancel = true;
  };
  REQUIRE_THROWS_AS(denoise(m, {}, progress), Cancelled);
  REQUIRE(reports > 0);
  REQUIRE(m.positions() == before);
}

// Denoising (docs/denoising.md): the noise estimate, the default pipeline (face normal mean shift,
// amount of smoothing chosen by SURE) and the paper preset. Noise goes, edges stay, the choice is
// close to the best in hindsight, threads change nothing, bad input and cancel leave the mesh alone.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <utility>

#include "geoshift/denoise.hpp"
#include "geoshift/denoise_request.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/smoothing.hpp"
#include "denoise_support.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

// Gaussian displacement along the vertex normals, σ = amount AEL: the noise model of the estimate.
Mesh withNormalNoise(const Mesh& clean, double amount, std::uint64_t seed) {
  Mesh m = clean;
  NoiseOptions o;
  o.amount = amount;
  o.distribution = NoiseDistribution::Gaussian;
  o.direction = NoiseDirection::Normal;
  o.seed = seed;
  addNoise(m, o);
  return m;
}

// One candidate of the default denoiser computed by itself: Taubin steps and passes at h_r, or
// Taubin alone (candidateTaubin), as the result reports them; to compare a result with it.
std::vector<Vec3> candidateAlone(const Mesh& noisy, int steps, int passes, bool taubinOnly, double hr, double noiseLevel) {
  Mesh m = noisy;
  if (passes > 0) {
    DenoiseOptions fixed;
    fixed.noiseLevel = noiseLevel;
    fixed.presmoothing = {steps};
    fixed.rangeBandwidths = {hr};
    fixed.fixedPasses = passes;
    denoise(m, fixed);
  } else {
    TaubinOptions t = taubinOnly ? DenoiseOptions{}.candidateTaubin : DenoiseOptions{}.supportSmoothing;
    t.iterations = steps;
    taubinSmooth(m, t);
  }
  return m.positions();
}

}  // namespace

TEST_CASE("the noise estimate recovers a known noise level and sees none on clean meshes", "[denoise][noise]") {
  const Mesh sphere = build(shapes::icosphere(5)), torus = build(shapes::torus(120, 40));
  for (const Mesh* clean : {&sphere, &torus}) {
    const NoiseEstimate none = estimateNoise(*clean);
    INFO("clean: " << none.level << " AEL from " << none.samples << " samples");
    REQUIRE(none.samples > clean->vertexCount() / 2);
    REQUIRE(none.level < 0.01);
    for (double amount : {0.05, 0.15, 0.3}) {
      const NoiseEstimate e = estimateNoise(withNormalNoise(*clean, amount, 7));
      INFO("σ " << amount << " AEL estimated as " << e.level);
      REQUIRE(e.level == Approx(amount).epsilon(0.15));
    }
  }
  // A box's creases and corners do not read as noise.
  REQUIRE(estimateNoise(build(shapes::box(12, 12, 12))).level < 0.02);
}

// The uniform reading of the paper's noise, |d| in [0, 0.5 AEL] in random directions, on a block.
TEST_CASE("default denoising of a noisy CAD block removes the noise and keeps the edges", "[denoise]") {
  const Mesh clean = build(shapes::box(12, 12, 12));
  for (NoiseDistribution dist : {NoiseDistribution::Uniform, NoiseDistribution::Fixed}) {
    const Mesh noisy = withNoise(clean, 0.5, 3, dist);
    Mesh m = noisy;
    const DenoiseResult r = denoise(m);
    const double before = rmsTo(noisy, clean), after = rmsTo(m, clean);
    INFO("RMS " << before << " -> " << after << ", crease error " << meanFeatureEdgeError(clean, noisy) << " -> "
                << meanFeatureEdgeError(clean, m) << "°, noise " << r.noiseLevel << " AEL, Taubin "
                << r.presmoothingSteps << " + " << r.passes << " passes");
    REQUIRE(r.noiseEstimated);
    REQUIRE(r.noiseLevel > 0.1);
    REQUIRE(r.passes >= 1);
    REQUIRE(after < 0.4 * before);
    REQUIRE(meanFeatureEdgeError(clean, m) < 8);
    REQUIRE(meanNormalAngleError(m, clean) < 0.4 * meanNormalAngleError(noisy, clean));
    REQUIRE(flippedFaces(clean, m) <= flippedFaces(clean, noisy));
    for (const Vec3& p : m.positions()) REQUIRE(p.allFinite());
  }
}

// Impulsive noise (10% of the vertices moved, N(0, 0.5 AEL)) is told from Gaussian noise by the
// kurtosis of the winner's displacement; the correction then leaves most vertices exactly where the
// input had them, and the result is nearer the clean sphere than the winner, in position and normals.
TEST_CASE("impulsive noise is recognised and the untouched vertices mostly stay", "[denoise][impulsive]") {
  const Mesh clean = build(shapes::icosphere(4));
  const Mesh impulsive = withNoise(clean, 0.5, 6, NoiseDistribution::Impulsive);
  Mesh with = impulsive, without = impulsive;
  const DenoiseResult r = denoise(with);
  DenoiseOptions off;
  off.impulseShrink = 0;
  const DenoiseResult r0 = denoise(without, off);
  INFO("kurtosis " << r.displacementKurtosis << "; RMS noisy " << rmsTo(impulsive, clean) << ", without "
                   << rmsTo(without, clean) << ", with " << rmsTo(with, clean));
  REQUIRE(r.impulseGarrote);
  REQUIRE_FALSE(r0.impulseGarrote);
  REQUIRE(r.displacementKurtosis == Approx(r0.displacementKurtosis));
  REQUIRE(r.displacementKurtosis > 6);
  REQUIRE(rmsTo(with, clean) < rmsTo(without, clean));
  REQUIRE(meanNormalAngleError(with, clean) < meanNormalAngleError(without, clean));
  int kept = 0;
  for (int v = 0; v < clean.vertexCount(); ++v) kept += with.position(v) == impulsive.position(v);
  INFO("kept " << kept << " of " << clean.vertexCount());
  REQUIRE(kept > 0.8 * clean.vertexCount());  // the noise moved 10%
  // Gaussian noise everywhere: the kurtosis stays near 3 and nothing is shrunk.
  Mesh gaussian = withNoise(clean, 0.3, 6, NoiseDistribution::Gaussian);
  const DenoiseResult rg = denoise(gaussian);
  INFO("Gaussian: kurtosis " << rg.displacementKurtosis);
  REQUIRE_FALSE(rg.impulseGarrote);
  REQUIRE(rg.displacementKurtosis < 6);

  // Asked for (the request's impulse "on": a trigger of 0), the correction runs under Gaussian noise
  // too, and there it is worse than none: every vertex carries noise, so keeping inputs keeps noise.
  // "off" keeps it from the impulsive sphere. The same winners: only the correction differs.
  Mesh forced = withNoise(clean, 0.3, 6, NoiseDistribution::Gaussian);
  const DenoiseResult rf = denoise(forced, denoiseSettings(ParamValues{{"impulse", std::string("on")}}).meanShift);
  INFO("Gaussian, forced: RMS " << rmsTo(forced, clean) << " against " << rmsTo(gaussian, clean));
  REQUIRE(rf.impulseGarrote);
  REQUIRE(rf.passes == rg.passes);
  REQUIRE(rmsTo(forced, clean) > rmsTo(gaussian, clean));
  Mesh refused = impulsive;
  const DenoiseResult rr = denoise(refused, denoiseSettings(ParamValues{{"impulse", std::string("off")}}).meanShift);
  REQUIRE_FALSE(rr.impulseGarrote);
  REQUIRE(refused.positions() == without.positions());
}

// SURE is an unbiased estimate of the error: the pass count it picks must be close to the best one
// in hindsight, found here by running every count and measuring against the clean mesh.
TEST_CASE("the passes SURE picks are nearly the best in hindsight", "[denoise][sure]") {
  const Mesh clean = build(shapes::torus(90, 30));
  const Mesh noisy = withNoise(clean, 0.5, 11, NoiseDistribution::Uniform);
  Mesh chosen = noisy;
  DenoiseOptions o;
  const DenoiseResult r = denoise(chosen, o);
  double best = std::numeric_limits<double>::infinity();
  int bestPasses = -1;
  for (int t = 1; t <= 12; ++t) {
    Mesh m = noisy;
    DenoiseOptions f = o;
    f.presmoothing = {r.presmoothingSteps};
    f.fixedPasses = t;
    denoise(m, f);
    const double e = rmsTo(m, clean);
    if (e < best) {
      best = e;
      bestPasses = t;
    }
  }
  INFO("SURE: Taubin " << r.presmoothingSteps << " + " << r.passes << " passes, RMS " << rmsTo(chosen, clean)
                       << "; best in hindsight " << bestPasses << " passes, RMS " << best << "; estimated error "
                       << r.estimatedError << " AEL");
  REQUIRE(rmsTo(chosen, clean) <= 1.1 * best);
  // The estimated error is that along the normals of the input after a few Taubin steps: it must be
  // near the true one measured the same way (SURE is unbiased, but one probe and one noise draw
  // leave it some spread; it is reported as 0 when it comes out negative).
  Mesh smoothed = noisy;
  TaubinOptions t = o.supportSmoothing;
  t.iterations = o.riskNormalSmoothing;
  taubinSmooth(smoothed, t);
  const std::vector<Vec3> normals = vertexNormals(smoothed);
  double sum = 0;
  for (int v = 0; v < chosen.vertexCount(); ++v) {
    const double d = (chosen.position(v) - clean.position(v)).dot(normals[v]);
    sum += d * d;
  }
  const double trueError = std::sqrt(sum / chosen.vertexCount()) / averageEdgeLength(noisy);
  INFO("true error along the normals " << trueError << " AEL");
  REQUIRE(r.estimatedError >= 0);
  REQUIRE(std::abs(r.estimatedError - trueError) < 0.25 * r.noiseLevel);
  REQUIRE(trueError < 0.5 * r.noiseLevel);
}

TEST_CASE("strength smooths more, a given noise level is used as given", "[denoise]") {
  const Mesh clean = build(shapes::icosphere(4));
  const Mesh noisy = withNoise(clean, 0.4, 5, NoiseDistribution::Uniform);
  Mesh a = noisy, b = noisy, c = noisy;
  DenoiseOptions o;
  const DenoiseResult ra = denoise(a, o);
  o.strength = 3;
  const DenoiseResult rb = denoise(b, o);
  REQUIRE(rb.noiseLevel == Approx(3 * ra.noiseLevel));
  REQUIRE(rb.presmoothingSteps + rb.passes >= ra.presmoothingSteps + ra.passes);
  o = {};
  o.noiseLevel = 0.123;
  const DenoiseResult rc = denoise(c, o);
  REQUIRE_FALSE(rc.noiseEstimated);
  REQUIRE(rc.noiseLevel == 0.123);
}

TEST_CASE("fine detail read as noise: the Taubin candidates' bound takes the noise level back down", "[denoise][noise]") {
  // A sphere with bumps six edges across and 1.2 AEL high: the noise estimate's local fits read
  // them as noise.
  Mesh clean = build(shapes::icosphere(4));
  const double ael = averageEdgeLength(clean), wave = 2 * std::numbers::pi / (6 * ael);
  for (Vec3& p : clean.positions()) {
    const Vec3 u = p.normalized();
    p = u * (1 + 1.2 * ael * std::sin(wave * u.x()) * std::sin(wave * u.y()) * std::sin(wave * u.z()));
  }
  const double amount = 0.15;
  const Mesh noisy = withNormalNoise(clean, amount, 3);
  Mesh a = noisy, b = noisy, c = noisy;
  DenoiseOptions o;
  o.highFrequencyLevel = false;  // the level refined from the candidates (the fallback)
  const DenoiseResult withBound = denoise(a, o);
  o.detailBoundRatio = 0;
  const DenoiseResult without = denoise(b, o);
  const double estimate = estimateNoise(noisy).level;
  INFO("true " << amount << " AEL, estimate " << estimate << ", refined " << without.noiseLevel << ", with the bound "
               << withBound.noiseLevel << "; RMS " << rmsTo(b, clean) / ael << " → " << rmsTo(a, clean) / ael << " AEL");
  REQUIRE(estimate > 1.3 * amount);  // the detail reads as noise
  REQUIRE(withBound.noiseLevel < 0.9 * without.noiseLevel);
  REQUIRE(std::abs(withBound.noiseLevel - amount) < std::abs(without.noiseLevel - amount));
  REQUIRE(rmsTo(a, clean) < rmsTo(b, clean));
  // The default reads the level from the top of the spectrum, where bumps six edges across hardly
  // reach: nearer the truth than either, and a result at least as close to the clean sphere.
  const DenoiseResult high = denoise(c);
  INFO("high-frequency level " << high.noiseLevel << ", RMS " << rmsTo(c, clean) / ael << " AEL");
  REQUIRE(std::abs(high.noiseLevel - amount) < std::abs(withBound.noiseLevel - amount));
  REQUIRE(high.noiseLevel == Approx(amount).epsilon(0.08));
  REQUIRE(rmsTo(c, clean) <= 1.02 * rmsTo(a, clean));
}

// The true noise level along the clean mesh's normals, in the noisy mesh's average edge lengths.
static double alongNormals(const Mesh& noisy, const Mesh& clean) {
  const std::vector<Vec3> n = vertexNormals(clean);
  double sum = 0;
  for (int v = 0; v < clean.vertexCount(); ++v) sum += std::pow((noisy.position(v) - clean.position(v)).dot(n[v]), 2);
  return std::sqrt(sum / clean.vertexCount()) / averageEdgeLength(noisy);
}

// docs/denoising.md#noise-estimate: the Laplacian twice, against its response to white noise, away
// from creases. A plain mean: right for fixed and uniform magnitudes too, where the quadric
// estimate's lower half (calibrated for Gaussian noise) reads fixed-magnitude noise high.
TEST_CASE("the high-frequency noise level reads any distribution, and no curvature or crease", "[denoise][noise]") {
  const Mesh sphere = build(shapes::icosphere(5)), torus = build(shapes::torus(120, 40));
  ParallelOptions one, four;
  one.threads = 1;
  four.threads = 4;
  for (const Mesh* clean : {&sphere, &torus}) {
    const double none = highFrequencyNoiseLevel(*clean);
    INFO("clean: " << none);
    REQUIRE(none < 0.01);
    for (NoiseDistribution d : {NoiseDistribution::Fixed, NoiseDistribution::Uniform, NoiseDistribution::Gaussian}) {
      for (double amount : {0.1, 0.5}) {
        const Mesh noisy = withNoise(*clean, amount, 7, d);
        const double truth = alongNormals(noisy, *clean), high = highFrequencyNoiseLevel(noisy, one);
        const double quadric = estimateNoise(noisy).level;
        INFO("distribution " << static_cast<int>(d) << ", amount " << amount << ": true " << truth << ", high "
                             << high << ", quadric " << quadric);
        REQUIRE(high == Approx(truth).epsilon(0.05));
        REQUIRE(highFrequencyNoiseLevel(noisy, four) == high);  // the same bits on any thread count
        if (d == NoiseDistribution::Fixed) REQUIRE(std::abs(high - truth) < std::abs(quadric - truth));
      }
    }
  }
  // A box's creases and corners are left out; the level does not depend on the mesh's scale.
  const Mesh box = build(shapes::box(12, 12, 12));
  REQUIRE(highFrequencyNoiseLevel(box) < 0.02);
  Mesh noisyBox = withNormalNoise(box, 0.2, 5), scaled = noisyBox;
  for (Vec3& p : scaled.positions()) p *= 10;
  const double boxLevel = highFrequencyNoiseLevel(noisyBox);
  REQUIRE(boxLevel == Approx(0.2).epsilon(0.1));
  REQUIRE(highFrequencyNoiseLevel(scaled) == Approx(boxLevel).epsilon(1e-9));
  // Every vertex within three rings of the boundary: nothing to read.
  REQUIRE(highFrequencyNoiseLevel(build(shapes::grid(5, 0.2))) == 0);
}

// docs/denoising.md#impulsive-noise: the kurtosis of the same frequencies tells impulsive noise from
// the rest without looking at a winner: spikes keep their tails through a local filter, a sum of
// many bounded or Gaussian values does not.
TEST_CASE("the high-frequency kurtosis tells impulsive noise, and triggers the correction where the winner's does not",
          "[denoise][noise][impulsive]") {
  const Mesh sphere = build(shapes::icosphere(4));
  ParallelOptions four;
  four.threads = 4;
  for (std::uint64_t seed : {3, 8}) {
    const double impulsive = highFrequencyNoise(withNoise(sphere, 0.3, seed, NoiseDistribution::Impulsive)).kurtosis;
    const double gaussian = highFrequencyNoise(withNormalNoise(sphere, 0.3, seed)).kurtosis;
    // Gaussian in a random direction: along N a Gaussian times a uniform cosine, heavier tailed (5.4).
    const double tilted = highFrequencyNoise(withNoise(sphere, 0.3, seed, NoiseDistribution::Gaussian)).kurtosis;
    const double fixed = highFrequencyNoise(withNoise(sphere, 0.3, seed, NoiseDistribution::Fixed)).kurtosis;
    const double uniform = highFrequencyNoise(withNoise(sphere, 0.3, seed, NoiseDistribution::Uniform)).kurtosis;
    INFO("seed " << seed << ": impulsive " << impulsive << ", Gaussian along N " << gaussian << ", in random directions "
                 << tilted << ", fixed " << fixed << ", uniform " << uniform);
    REQUIRE(impulsive > 2 * DenoiseOptions{}.impulseSpectrumKurtosis);
    REQUIRE(gaussian == Approx(3).margin(0.5));
    REQUIRE(tilted > gaussian);
    REQUIRE(tilted < DenoiseOptions{}.impulseSpectrumKurtosis);
    REQUIRE(fixed < 3);  // along N a fixed length in a random direction is uniform: lighter tails
    REQUIRE(uniform < DenoiseOptions{}.impulseSpectrumKurtosis);
    const Mesh noisy = withNoise(sphere, 0.3, seed, NoiseDistribution::Impulsive);
    const HighFrequencyNoise h = highFrequencyNoise(noisy), h4 = highFrequencyNoise(noisy, four);
    REQUIRE((h4.level == h.level && h4.kurtosis == h.kurtosis));  // the same bits on any thread count
  }
  REQUIRE(highFrequencyNoise(sphere).kurtosis > 0);  // a clean sphere: rounding only, but a ratio all the same
  REQUIRE(highFrequencyNoise(build(shapes::grid(5, 0.2))).kurtosis == 0);  // nothing to read

  // With the winner's trigger out of reach, the spectrum's alone corrects the outliers, and the
  // result is nearer the clean sphere than without it; Gaussian noise sets off neither.
  const Mesh noisy = withNoise(sphere, 0.5, 6, NoiseDistribution::Impulsive);
  Mesh with = noisy, without = noisy;
  DenoiseOptions o;
  o.impulseKurtosis = 1e9;
  const DenoiseResult r = denoise(with, o);
  o.impulseSpectrumKurtosis = 0;
  const DenoiseResult r0 = denoise(without, o);
  INFO("spectrum kurtosis " << r.spectrumKurtosis << "; RMS without " << rmsTo(without, sphere) << ", with "
                            << rmsTo(with, sphere));
  REQUIRE(r.impulseGarrote);
  REQUIRE_FALSE(r0.impulseGarrote);
  REQUIRE(r.spectrumKurtosis > DenoiseOptions{}.impulseSpectrumKurtosis);
  REQUIRE(rmsTo(with, sphere) < rmsTo(without, sphere));
  Mesh gaussian = withNoise(sphere, 0.3, 6, NoiseDistribution::Gaussian);
  const DenoiseResult rg = denoise(gaussian);
  REQUIRE_FALSE(rg.impulseGarrote);
  REQUIRE(rg.spectrumKurtosis < DenoiseOptions{}.impulseSpectrumKurtosis);
  // A given noise level: the spectrum is read for the trigger all the same.
  Mesh given = noisy;
  o = {};
  o.noiseLevel = 0.1;
  o.impulseKurtosis = 1e9;
  REQUIRE(denoise(given, o).impulseGarrote);
}

// docs/denoising.md#the-noise-level, "A reading of few vertices": the vertices read are those more
// than three rings from every crease and boundary; where they are fewer than
// highFrequencyMinSamples the reading is blended with the refined level by w = n / (n + 5), and its
// kurtosis does not trigger the impulse correction.
TEST_CASE("a high-frequency reading of few vertices is weighted by how many, and its kurtosis not used",
          "[denoise][noise]") {
  // Counted against a breadth-first search: a grid's vertices more than three rings from its boundary.
  for (int n : {9, 12, 20}) {
    const Mesh grid = withNormalNoise(build(shapes::grid(n)), 0.05, 3);
    std::vector<int> ring(grid.vertexCount(), -1), frontier;
    for (int v = 0; v < grid.vertexCount(); ++v)
      if (grid.isBoundaryVertex(v)) {
        ring[v] = 0;
        frontier.push_back(v);
      }
    for (int r = 1; r <= 3; ++r) {
      std::vector<int> next;
      for (int v : frontier)
        for (int w : grid.neighbors(v))
          if (ring[w] < 0) {
            ring[w] = r;
            next.push_back(w);
          }
      frontier.swap(next);
    }
    const int far = static_cast<int>(std::count(ring.begin(), ring.end(), -1));
    INFO("grid " << n);
    REQUIRE(highFrequencyNoise(grid).samples == far);
  }
  REQUIRE(highFrequencyNoise(build(shapes::icosphere(3))).samples == 642);  // no crease, no boundary: all

  // A box of 9 × 9 × 9 cells: 4 vertices read on each side, 24 in all; with noise a few fewer (the
  // smoothed copy bends by more than 30° here and there).
  const Mesh box = build(shapes::box(9, 9, 9));
  REQUIRE(highFrequencyNoise(box).samples == 24);
  const Mesh noisy = withNormalNoise(box, 0.15, 4);
  const HighFrequencyNoise high = highFrequencyNoise(noisy);
  REQUIRE(high.samples > 0);
  REQUIRE(high.samples < DenoiseOptions{}.highFrequencyMinSamples);
  REQUIRE(high.level > 0);
  Mesh refinedMesh = noisy, blendedMesh = noisy, readingMesh = noisy;
  DenoiseOptions refined;
  refined.highFrequencyLevel = false;  // the level refined from the candidates alone
  const DenoiseResult rr = denoise(refinedMesh, refined);
  const DenoiseResult rb = denoise(blendedMesh);
  DenoiseOptions reading;
  reading.highFrequencyMinSamples = 0;  // the reading itself, however few its vertices
  const DenoiseResult rd = denoise(readingMesh, reading);
  const double w = high.samples / (high.samples + 5.0);
  INFO("reading " << high.level << ", refined " << rr.noiseLevel << ", blended " << rb.noiseLevel);
  REQUIRE(rd.noiseLevel == Approx(high.level).epsilon(1e-12));
  REQUIRE(rb.noiseLevel == Approx(std::exp(w * std::log(high.level) + (1 - w) * std::log(rr.noiseLevel))).epsilon(1e-9));
  REQUIRE(rd.spectrumKurtosis == Approx(high.kurtosis).epsilon(1e-12));
  REQUIRE(rb.spectrumKurtosis == 0);
  // At the bar the reading is used as it is.
  DenoiseOptions at;
  at.highFrequencyMinSamples = high.samples;
  Mesh atMesh = noisy;
  REQUIRE(denoise(atMesh, at).noiseLevel == Approx(high.level).epsilon(1e-12));
}

// The winner's kurtosis is vetoed where a spectrum read from many vertices has light tails: fixed
// noise on a sphere, the winner's trigger set to fire on anything (kurtosis above 1).
TEST_CASE("a light-tailed spectrum vetoes the winner's impulse trigger", "[denoise][noise][impulsive]") {
  const Mesh sphere = build(shapes::icosphere(4));
  const Mesh noisy = withNoise(sphere, 0.3, 5, NoiseDistribution::Fixed);
  const HighFrequencyNoise high = highFrequencyNoise(noisy);
  INFO("spectrum kurtosis " << high.kurtosis << " over " << high.samples << " vertices");
  REQUIRE(high.kurtosis + 2 * std::sqrt(24.0 / high.samples) < DenoiseOptions{}.impulseSpectrumVeto);
  DenoiseOptions o;
  o.impulseKurtosis = 1;
  Mesh vetoed = noisy, fired = noisy, asked = noisy;
  REQUIRE_FALSE(denoise(vetoed, o).impulseGarrote);
  o.impulseSpectrumVeto = 0;
  REQUIRE(denoise(fired, o).impulseGarrote);
  // Asked for in any case (impulseKurtosis 0, the CLI's --impulse on): no veto.
  o = {};
  o.impulseKurtosis = 0;
  REQUIRE(denoise(asked, o).impulseGarrote);
  // Impulsive noise: heavy tails, no veto, the correction runs as before.
  Mesh spiky = withNoise(sphere, 0.3, 5, NoiseDistribution::Impulsive);
  REQUIRE(denoise(spiky).impulseGarrote);
}

// The spectrum's trigger alone (the winner's switched off) needs a reading of
// impulseSpectrumMinSamples vertices: impulsive noise on a sphere fires it at the sphere's own count
// and not one above.
TEST_CASE("the spectrum's impulse trigger needs enough vertices read", "[denoise][noise][impulsive]") {
  const Mesh noisy = withNoise(build(shapes::icosphere(3)), 0.3, 7, NoiseDistribution::Impulsive);
  const HighFrequencyNoise high = highFrequencyNoise(noisy);
  INFO("spectrum kurtosis " << high.kurtosis << " over " << high.samples << " vertices");
  REQUIRE(high.kurtosis > DenoiseOptions{}.impulseSpectrumKurtosis);
  REQUIRE(high.samples >= DenoiseOptions{}.impulseSpectrumMinSamples);
  DenoiseOptions o;
  o.impulseKurtosis = 1e9;  // the winner never says so
  Mesh byDefault = noisy, atCount = noisy, above = noisy;
  REQUIRE(denoise(byDefault, o).impulseGarrote);
  o.impulseSpectrumMinSamples = high.samples;
  REQUIRE(denoise(atCount, o).impulseGarrote);
  o.impulseSpectrumMinSamples = high.samples + 1;
  const DenoiseResult r = denoise(above, o);
  REQUIRE_FALSE(r.impulseGarrote);
  REQUIRE(r.spectrumKurtosis == Approx(high.kurtosis));  // still read and reported
}

// docs/denoising.md#the-noise-level ("Planes left untouched"). A box of flat sides: clean, every face
// lies in the plane of a neighbour and every vertex on a plane of its two-ring (level 0). A few
// vertices moved along the normal of their side, each four rings from the others and from the
// box's edges, are read exactly: a moved vertex at its displacement, every other vertex at 0 (it
// has an untouched face of its own side in its two-ring). Dense noise confirms almost no face, and
// a sphere's faces none.
TEST_CASE("the level read against untouched planes", "[denoise][noise]") {
  const Mesh box = build(shapes::box(12, 12, 12));
  const PlanarNoise clean = planarNoise(box);
  REQUIRE(clean.confirmedShare == 1);
  REQUIRE(clean.samples == box.vertexCount());
  REQUIRE(clean.level < 1e-12);

  Mesh spiky = box;
  double sum = 0;
  int moved = 0;
  const double cell = 1.0 / 12;
  for (int v = 0; v < spiky.vertexCount(); ++v) {
    Vec3& p = spiky.position(v);
    const double i = (p.x() + 0.5) / cell, j = (p.y() + 0.5) / cell;  // the box is [-1/2, 1/2]³
    const bool top = std::abs(p.z() - 0.5) < 1e-9;
    const auto at = [](double k) { return std::abs(k - 4) < 1e-6 || std::abs(k - 8) < 1e-6; };
    if (!top || !at(i) || !at(j)) continue;
    const double d = (moved % 2 ? -0.2 : 0.35) * cell * (1 + moved);
    p.z() += d;
    sum += d * d;
    ++moved;
  }
  REQUIRE(moved == 4);
  const PlanarNoise read = planarNoise(spiky);
  INFO("share " << read.confirmedShare << ", level " << read.level);
  REQUIRE(read.samples == spiky.vertexCount());
  REQUIRE(read.confirmedShare > 0.9);
  REQUIRE(read.level == Approx(std::sqrt(sum / spiky.vertexCount()) / averageEdgeLength(spiky)).epsilon(1e-9));

  const PlanarNoise dense = planarNoise(withNormalNoise(box, 0.3, 2));
  REQUIRE(dense.confirmedShare < 0.1);  // the gate is 0.5
  const PlanarNoise sphere = planarNoise(build(shapes::icosphere(3)));
  REQUIRE(sphere.confirmedShare == 0);
  REQUIRE(sphere.samples == 0);
  REQUIRE(sphere.level == 0);
}

// Where the spectrum reads too few vertices, a part of flat faces is measured against its planes: a
// clean coarse box comes back as it went in (the level refined from the candidates moved it), and
// sparse outliers on it are ranked with the planar reading.
TEST_CASE("a part of flat faces is measured against its planes where the spectrum reads too few vertices",
          "[denoise][noise]") {
  const Mesh box = build(shapes::box(5, 5, 5));
  REQUIRE(highFrequencyNoise(box).samples < DenoiseOptions{}.highFrequencyMinSamples);
  REQUIRE(box.vertexCount() >= DenoiseOptions{}.minPieceVertices);
  Mesh kept = box, refined = box;
  const DenoiseResult r = denoise(kept);
  REQUIRE(r.planarLevel);
  REQUIRE(r.keptInput);
  REQUIRE(kept.positions() == box.positions());
  DenoiseOptions off;
  off.planarLevelShare = 0;
  const DenoiseResult rr = denoise(refined, off);
  INFO("refined level " << rr.noiseLevel);
  REQUIRE_FALSE(rr.planarLevel);
  REQUIRE(refined.positions() != box.positions());

  const Mesh noisy = withNoise(box, 0.4, 3, NoiseDistribution::Impulsive);
  const PlanarNoise planar = planarNoise(noisy);
  REQUIRE(planar.confirmedShare >= DenoiseOptions{}.planarLevelShare);
  Mesh a = noisy, b = noisy;
  const DenoiseResult ra = denoise(a);
  REQUIRE(ra.planarLevel);
  REQUIRE(ra.noiseLevel == Approx(planar.level).epsilon(1e-9));
  REQUIRE(rmsTo(a, box) < rmsTo(noisy, box));
  DenoiseOptions above;
  above.planarLevelShare = std::min(1.0, planar.confirmedShare + 0.01);
  const DenoiseResult rb = denoise(b, above);
  REQUIRE_FALSE(rb.planarLevel);
  REQUIRE(rb.noiseLevel != Approx(planar.level).epsilon(1e-3));
}

// docs/denoising.md#impulsive-noise ("Vertices on untouched planes"): sparse outliers on a box. After
// the correction, every vertex back at its input position is one the noise did not move, and the
// result is closer to the box than without the rule.
TEST_CASE("after the impulse correction, vertices on untouched planes keep their input positions",
          "[denoise][impulsive]") {
  const Mesh box = build(shapes::box(12, 12, 12));
  const Mesh noisy = withNoise(box, 0.5, 4, NoiseDistribution::Impulsive);
  Mesh with = noisy, without = noisy;
  const DenoiseResult r = denoise(with);
  REQUIRE(r.impulseGarrote);
  REQUIRE(r.planarKept > 0);
  DenoiseOptions off;
  off.planarKeep = 0;
  const DenoiseResult r0 = denoise(without, off);
  REQUIRE(r0.planarKept == 0);
  int back = 0, untouched = 0;
  for (int v = 0; v < noisy.vertexCount(); ++v) {
    untouched += noisy.position(v) == box.position(v);
    if (with.position(v) != noisy.position(v) || without.position(v) == noisy.position(v)) continue;
    ++back;
    INFO("vertex " << v);
    REQUIRE(noisy.position(v) == box.position(v));
  }
  INFO(back << " back of " << untouched << " untouched");
  REQUIRE(back == r.planarKept);
  REQUIRE(rmsTo(with, box) < rmsTo(without, box));
}

TEST_CASE("default denoising gives the same bits for any thread count", "[denoise][threads]") {
  const Mesh noisy = withNoise(build(shapes::box(10, 8, 6)), 0.5, 4, NoiseDistribution::Uniform);
  Mesh one = noisy, two = noisy;
  DenoiseOptions o;
  o.threads = 1;
  const DenoiseResult r1 = denoise(one, o);
  o.threads = 2;
  const DenoiseResult r2 = denoise(two, o);
  REQUIRE(one.positions() == two.positions());
  REQUIRE(r1.passes == r2.passes);
  REQUIRE(r1.estimatedError == r2.estimatedError);
}

// docs/denoising.md#speed-and-memory (spatial order). A torus listed in random order: the passes
// run renumbered, which changes only the order of floating-point sums; the probe is the same, so is
// every choice, and the caller's numbering comes back, after a cancel too.
TEST_CASE("spatial order changes only the order of sums, and the caller's order comes back", "[denoise][order]") {
  TriangleSoup soup = shapes::torus(96, 48);
  {
    std::mt19937 rng(7);
    std::vector<int> to(soup.positions.size());
    std::iota(to.begin(), to.end(), 0);
    std::shuffle(to.begin(), to.end(), rng);
    std::vector<Vec3> p(soup.positions.size());
    for (size_t v = 0; v < to.size(); ++v) p[to[v]] = soup.positions[v];
    soup.positions = p;
    for (Face& f : soup.faces)
      for (int& v : f) v = to[v];
    std::shuffle(soup.faces.begin(), soup.faces.end(), rng);
  }
  const Mesh noisy = withNoise(build(soup), 0.4, 3);
  const double ael = averageEdgeLength(noisy);
  Mesh spatial = noisy, caller = noisy;
  // Every candidate handed to onCandidate, in the caller's order either way.
  struct Candidate {
    int steps, passes;
    std::vector<Vec3> x;
  };
  std::vector<Candidate> seenOn, seenOff;
  DenoiseOptions on, off;
  on.onCandidate = [&](int steps, int passes, const std::vector<Vec3>& x, double) {
    seenOn.push_back({steps, passes, x});
  };
  off.onCandidate = [&](int steps, int passes, const std::vector<Vec3>& x, double) {
    seenOff.push_back({steps, passes, x});
  };
  off.spatialOrder = false;
  const DenoiseResult a = denoise(spatial, on), b = denoise(caller, off);
  REQUIRE(a.spatialOrder);
  REQUIRE_FALSE(b.spatialOrder);
  REQUIRE(a.farAdjacencies > 0.1);
  REQUIRE(a.presmoothingSteps == b.presmoothingSteps);
  REQUIRE(a.taubinOnly == b.taubinOnly);
  REQUIRE(a.passes == b.passes);
  REQUIRE(a.rangeBandwidth == b.rangeBandwidth);
  REQUIRE(a.passesRun == b.passesRun);
  REQUIRE(a.tieProbes == b.tieProbes);
  REQUIRE(a.noiseLevel == Approx(b.noiseLevel).epsilon(1e-9));
  REQUIRE(a.passes > 0);
  double farthest = 0;
  for (int v = 0; v < noisy.vertexCount(); ++v)
    farthest = std::max(farthest, (spatial.position(v) - caller.position(v)).norm());
  INFO("largest difference " << farthest / ael << " AEL");
  REQUIRE(farthest < 1e-9 * ael);
  REQUIRE(seenOn.size() == seenOff.size());
  REQUIRE(seenOn.size() > 10);
  double candidateFarthest = 0;
  for (size_t i = 0; i < seenOn.size(); ++i) {
    REQUIRE(seenOn[i].steps == seenOff[i].steps);
    REQUIRE(seenOn[i].passes == seenOff[i].passes);
    for (int v = 0; v < noisy.vertexCount(); ++v)
      candidateFarthest = std::max(candidateFarthest, (seenOn[i].x[v] - seenOff[i].x[v]).norm());
  }
  INFO("largest difference between the candidates handed out " << candidateFarthest / ael << " AEL");
  REQUIRE(candidateFarthest < 1e-9 * ael);
  REQUIRE(spatial.faces() == noisy.faces());
  for (int h = 0; h < noisy.halfedgeCount(); ++h) REQUIRE(spatial.twin(h) == noisy.twin(h));
  for (int v = 0; v < noisy.vertexCount(); ++v) REQUIRE(spatial.halfedge(v) == noisy.halfedge(v));
  // The agreement is not that of two runs that moved nothing: the vertices moved by a good part of
  // the noise.
  double moved = 0;
  for (int v = 0; v < noisy.vertexCount(); ++v) moved += (spatial.position(v) - noisy.position(v)).squaredNorm();
  REQUIRE(std::sqrt(moved / noisy.vertexCount()) > 0.1 * ael);

  // Cancelled half-way, renumbered: the mesh as it was, bit for bit.
  Mesh cancelled = noisy;
  std::atomic<bool> cancel{false};
  Progress progress;
  progress.cancel = &cancel;
  progress.report = [&](double f, std::string_view) {
    if (f > 0.5) cancel = true;
  };
  REQUIRE_THROWS_AS(denoise(cancelled, DenoiseOptions{}, progress), Cancelled);
  REQUIRE(cancelled.positions() == noisy.positions());
  REQUIRE(cancelled.faces() == noisy.faces());
  for (int h = 0; h < noisy.halfedgeCount(); ++h) REQUIRE(cancelled.twin(h) == noisy.twin(h));
  for (int v = 0; v < noisy.vertexCount(); ++v) REQUIRE(cancelled.halfedge(v) == noisy.halfedge(v));
}

// docs/denoising.md#ties-between-starts. A margin wider than any rank makes every start a
// contender, so the tie is settled on any mesh: the result is then exactly the candidate reported,
// computed again alone, whichever contender's positions the settling kept; no margin, no tie.
TEST_CASE("a tie between starts is settled by more probes, and the result is the candidate reported", "[denoise][tie]") {
  const Mesh noisy = withNoise(build(shapes::box(10, 8, 6)), 0.5, 4, NoiseDistribution::Uniform);
  DenoiseOptions o;
  o.tieMargin = 1e9;
  Mesh m = noisy;
  const DenoiseResult r = denoise(m, o);
  INFO("Taubin " << r.presmoothingSteps << " + " << r.passes << " passes at h_r " << r.rangeBandwidth << ", "
                 << r.tieProbes << " more probes");
  REQUIRE_FALSE(r.impulseGarrote);
  REQUIRE(r.tieProbes >= 1);
  REQUIRE(r.tieProbes <= o.tieProbes);

  REQUIRE(m.positions() == candidateAlone(noisy, r.presmoothingSteps, r.passes, r.taubinOnly, r.rangeBandwidth, r.noiseLevel));

  // Threads change nothing in the settling either.
  Mesh one = noisy;
  o.threads = 1;
  const DenoiseResult r1 = denoise(one, o);
  REQUIRE(one.positions() == m.positions());
  REQUIRE(r1.tieProbes == r.tieProbes);

  // No margin: no contender but the leader, no probe, the same as without settling.
  Mesh none = noisy, off = noisy;
  DenoiseOptions noMargin, noProbes;
  noMargin.tieMargin = 0;
  noProbes.tieProbes = 0;
  REQUIRE(denoise(none, noMargin).tieProbes == 0);
  REQUIRE(denoise(off, noProbes).tieProbes == 0);
  REQUIRE(none.positions() == off.positions());
}

// docs/denoising.md#the-blend-of-least-risk. The result is the winner, the best candidate of the
// other family and the best with passes from the other start, each computed again alone, mixed with
// the weights reported in that order; without blending, the winner alone.
TEST_CASE("the winner is blended with the other family's best and the other start's", "[denoise][blend]") {
  const Mesh noisy = withNoise(build(shapes::box(10, 8, 6)), 0.5, 4, NoiseDistribution::Uniform);
  // The widest spread the options allow: both are computed and take about half the weight.
  DenoiseOptions wide;
  wide.blendSpread = 1000;
  Mesh m = noisy;
  const DenoiseResult r = denoise(m, wide);
  auto recipe = [](const DenoiseResult::Blend& b) {
    return "Taubin " + std::to_string(b.presmoothingSteps) + (b.taubinOnly ? " alone" : " + " + std::to_string(b.passes) + " passes") +
           " (" + std::to_string(b.weight) + ")";
  };
  INFO("winner: Taubin " << r.presmoothingSteps << (r.taubinOnly ? " alone" : " + " + std::to_string(r.passes) + " passes")
                         << "; blended with " << recipe(r.blend) << ", then with " << recipe(r.startBlend));
  REQUIRE_FALSE(r.impulseGarrote);
  REQUIRE_FALSE(r.keptInput);
  REQUIRE(r.blend.weight > 0.4);
  REQUIRE(r.blend.weight < 0.6);
  REQUIRE(r.blend.taubinOnly != r.taubinOnly);
  REQUIRE(r.startBlend.weight > 0.4);
  REQUIRE(r.startBlend.weight < 0.6);
  REQUIRE_FALSE(r.startBlend.taubinOnly);
  const int start = r.taubinOnly ? r.blend.presmoothingSteps : r.presmoothingSteps;
  REQUIRE(r.startBlend.presmoothingSteps != start);
  const std::vector<Vec3> winner = candidateAlone(noisy, r.presmoothingSteps, r.passes, r.taubinOnly, r.rangeBandwidth, r.noiseLevel);
  const std::vector<Vec3> other =
      candidateAlone(noisy, r.blend.presmoothingSteps, r.blend.passes, r.blend.taubinOnly, r.blend.rangeBandwidth, r.noiseLevel);
  const std::vector<Vec3> otherStart =
      candidateAlone(noisy, r.startBlend.presmoothingSteps, r.startBlend.passes, false, r.startBlend.rangeBandwidth, r.noiseLevel);
  REQUIRE(winner != other);
  REQUIRE(winner != otherStart);
  for (int v = 0; v < noisy.vertexCount(); ++v) {
    const Vec3 first = (1 - r.blend.weight) * winner[v] + r.blend.weight * other[v];
    const Vec3 expected = (1 - r.startBlend.weight) * first + r.startBlend.weight * otherStart[v];
    REQUIRE(m.position(v) == expected);
  }

  // Threads change nothing in the blend either.
  Mesh one = noisy;
  wide.threads = 1;
  const DenoiseResult r1 = denoise(one, wide);
  REQUIRE(r1.blend.weight == r.blend.weight);
  REQUIRE(r1.startBlend.weight == r.startBlend.weight);
  REQUIRE(one.positions() == m.positions());

  // The default's spread weighs by the risk: weights within [0, 1].
  Mesh def = noisy;
  const DenoiseResult rd = denoise(def, DenoiseOptions{});
  REQUIRE(rd.blend.weight >= 0);
  REQUIRE(rd.blend.weight <= 1);
  REQUIRE(rd.startBlend.weight >= 0);
  REQUIRE(rd.startBlend.weight <= 1);

  // No spread: the winner alone, and nothing reported.
  DenoiseOptions off;
  off.blendSpread = 0;
  Mesh plain = noisy;
  const DenoiseResult r0 = denoise(plain, off);
  REQUIRE(r0.blend.weight == 0);
  REQUIRE(r0.startBlend.weight == 0);
  REQUIRE(plain.positions() == candidateAlone(noisy, r0.presmoothingSteps, r0.passes, r0.taubinOnly, r0.rangeBandwidth, r0.noiseLevel));
}

// A tie the probes leave unsettled goes to the contender whose normals turn least (tieByNormals):
// the contenders the leader by mean rank does not lead by tieStandardErrors include the leader
// itself, so the result turns no more than the leader's. Held unsettled here by a lead no probe can
// reach; every start a contender.
TEST_CASE("a tie left unsettled by the probes goes to the normals that turn least", "[denoise][tie]") {
  const std::vector<Mesh> tried = {build(shapes::box(10, 8, 6)), build(shapes::torus(32, 16)), build(shapes::icosphere(3))};
  int changed = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Mesh noisy = withNoise(tried[seed % 3], 0.5, seed, NoiseDistribution::Uniform);
    DenoiseOptions o;
    o.tieMargin = 1e9;
    o.tieProbes = 2;
    o.tieStandardErrors = 1e9;
    o.blendSpread = 0;  // the contender's own normals: without the other candidates blended in
    Mesh with = noisy, without = noisy;
    const DenoiseResult r = denoise(with, o);
    o.tieByNormals = false;
    const DenoiseResult r0 = denoise(without, o);
    const double turn = meanNormalTurn(with, with.positions()), leaderTurn = meanNormalTurn(without, without.positions());
    INFO("noise seed " << seed << ": Taubin " << r.presmoothingSteps << " + " << r.passes << " against "
                       << r0.presmoothingSteps << " + " << r0.passes << ", turn " << turn << " against " << leaderTurn);
    REQUIRE(r.tieProbes == 2);
    REQUIRE(r0.tieProbes == 2);
    REQUIRE(r.tieByNormals);
    REQUIRE_FALSE(r0.tieByNormals);
    REQUIRE(turn <= leaderTurn);
    if (with.positions() != without.positions()) {
      ++changed;
      REQUIRE(turn < leaderTurn);
    }
  }
  CHECK(changed > 0);
  // Settled by the probes (the default lead of 4 standard errors, one probe on this box): the
  // normals are not asked.
  Mesh settled = withNoise(tried[0], 0.5, 1, NoiseDistribution::Uniform);
  DenoiseOptions o;
  o.tieMargin = 1e9;
  o.tieProbes = 1;
  REQUIRE_FALSE(denoise(settled, o).tieByNormals);
}

// docs/denoising.md#taubin-only-candidates. A smooth sphere under dense Gaussian noise, where the
// candidates with passes may start only from the raw input and run at most one pass: smoothing it
// with many Taubin steps is far better, so a Taubin-only candidate must win, and the result must be
// exactly that smoothing of the input, at one of the step counts offered. A margin wider than any
// rank keeps the candidates with passes.
TEST_CASE("a Taubin-only candidate wins where passes cannot smooth enough, and is exactly its smoothing", "[denoise][taubin-only]") {
  const Mesh clean = build(shapes::icosphere(4));
  const Mesh noisy = withNormalNoise(clean, 0.5, 21);
  DenoiseOptions o;
  o.presmoothing = {0};
  o.maxPasses = 1;
  Mesh m = noisy;
  const DenoiseResult r = denoise(m, o);
  INFO("Taubin " << r.presmoothingSteps << " + " << r.passes << " passes, Taubin only: " << r.taubinOnly);
  REQUIRE(r.taubinOnly);
  REQUIRE(r.passes == 0);
  REQUIRE(std::find(o.taubinOnlySteps.begin(), o.taubinOnlySteps.end(), r.presmoothingSteps) != o.taubinOnlySteps.end());
  Mesh alone = noisy;
  TaubinOptions t = o.candidateTaubin;
  t.iterations = r.presmoothingSteps;
  taubinSmooth(alone, t);
  REQUIRE(m.positions() == alone.positions());
  REQUIRE(rmsTo(m, clean) < 0.5 * rmsTo(noisy, clean));

  // The same with one thread: the same bits.
  Mesh one = noisy;
  o.threads = 1;
  denoise(one, o);
  REQUIRE(one.positions() == m.positions());

  // A margin no Taubin-only candidate can lead by: a candidate with passes wins.
  Mesh kept = noisy;
  o.taubinOnlyMargin = 1e9;
  const DenoiseResult rk = denoise(kept, o);
  REQUIRE_FALSE(rk.taubinOnly);
  REQUIRE(rk.presmoothingSteps == 0);

  // None offered (the request's taubinOnly 0): a candidate with passes wins, by the request's path.
  Mesh none = noisy;
  const DenoiseOptions n =
      denoiseSettings(ParamValues{{"taubinOnly", 0.0}, {"presmoothing", 0.0}, {"maxPasses", 1.0}}).meanShift;
  const DenoiseResult rn = denoise(none, n);
  REQUIRE_FALSE(rn.taubinOnly);
  REQUIRE(rn.presmoothingSteps == 0);
  REQUIRE(rmsTo(none, clean) > rmsTo(m, clean));
}

// The input is a candidate of known risk, σ² (docs/denoising.md#the-input-as-a-candidate): a CAD
// block denoised once and then again comes back from the second run as it went in, where without
// the input as a candidate the second run rounds its creases further (and the impulse correction,
// taking the creases for outliers, moves them alone). Noise is never kept.
TEST_CASE("a mesh no candidate would bring closer to the noise-free surface is returned as it was", "[denoise][input]") {
  const Mesh clean = build(shapes::box(12, 12, 12));
  const Mesh noisy = withNoise(clean, 0.5, 3);
  Mesh once = noisy;
  const DenoiseResult first = denoise(once);
  INFO("first: Taubin " << first.presmoothingSteps << " + " << first.passes << " passes, noise " << first.noiseLevel);
  REQUIRE_FALSE(first.keptInput);
  REQUIRE(rmsTo(once, clean) < 0.4 * rmsTo(noisy, clean));

  Mesh twice = once;
  const DenoiseResult second = denoise(twice);
  INFO("second: noise " << second.noiseLevel << " AEL, estimated error " << second.estimatedError);
  REQUIRE(second.keptInput);
  REQUIRE(twice.positions() == once.positions());
  REQUIRE(second.presmoothingSteps == 0);
  REQUIRE(second.passes == 0);
  REQUIRE_FALSE(second.taubinOnly);
  REQUIRE_FALSE(second.impulseGarrote);
  REQUIRE(second.passesRun > 0);                                   // the candidates were scored, and lost
  REQUIRE(second.estimatedError == Approx(second.noiseLevel));    // the input's error is the noise

  DenoiseOptions without;
  without.inputCandidate = false;
  Mesh moved = once;
  const DenoiseResult other = denoise(moved, without);
  REQUIRE_FALSE(other.keptInput);
  REQUIRE(moved.positions() != once.positions());
  REQUIRE(meanFeatureEdgeError(clean, moved) > meanFeatureEdgeError(clean, once));

  // The same for any thread count: the comparison reads the same sums.
  DenoiseOptions one;
  one.threads = 1;
  Mesh serial = once;
  REQUIRE(denoise(serial, one).keptInput);
  REQUIRE(serial.positions() == once.positions());
}

TEST_CASE("denoising a clean plane leaves it planar", "[denoise]") {
  for (DenoisePreset preset : {DenoisePreset::Default, DenoisePreset::Paper}) {
    Mesh m = build(shapes::grid(20, 0.3));
    DenoiseOptions o;
    o.preset = preset;
    denoise(m, o);
    for (const Vec3& p : m.positions()) REQUIRE(std::abs(p.z()) < 1e-9);
  }
}

// Open boundaries, two components, a sliver: the denoiser runs through, nothing folds or goes NaN.
TEST_CASE("default denoising copes with boundaries, components and slivers", "[denoise]") {
  TriangleSoup soup = shapes::grid(24);
  TriangleSoup ball = shapes::icosphere(3, 0.3);
  const int offset = static_cast<int>(soup.positions.size());
  for (const Vec3& p : ball.positions) soup.positions.push_back(p + Vec3(0.5, 0.5, 1.0));
  for (const Face& f : ball.faces) soup.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  // A sliver: a face whose third corner sits almost on its first edge.
  soup.positions.push_back(Vec3(2.0, 0, 0));
  soup.positions.push_back(Vec3(2.2, 0, 0));
  soup.positions.push_back(Vec3(2.1, 1e-9, 0));
  const int s = static_cast<int>(soup.positions.size()) - 3;
  soup.faces.push_back({s, s + 1, s + 2});
  const Mesh clean = build(soup);
  const Mesh noisy = withNoise(clean, 0.3, 9, NoiseDistribution::Uniform);
  Mesh m = noisy;
  const DenoiseResult r = denoise(m);
  INFO("RMS " << rmsTo(noisy, clean) << " -> " << rmsTo(m, clean));
  for (const Vec3& p : m.positions()) REQUIRE(p.allFinite());
  REQUIRE(r.noiseLevel > 0);
  REQUIRE(rmsTo(m, clean) < 0.7 * rmsTo(noisy, clean));
}

// docs/denoising.md#small-pieces: pieces of a few vertices keep their positions, and the rest is
// denoised exactly as it would be alone, under both presets.
TEST_CASE("pieces too small to denoise keep their positions and do not change the rest", "[denoise][pieces]") {
  const Mesh ball = withNoise(build(shapes::icosphere(3)), 0.3, 5);
  // The noisy ball, a small tetrahedron about two of its edges across and a lone triangle.
  auto add = [](TriangleSoup& soup, const TriangleSoup& piece, const Vec3& at, double scale) {
    const int offset = static_cast<int>(soup.positions.size());
    for (const Vec3& p : piece.positions) soup.positions.push_back(at + scale * p);
    for (const Face& f : piece.faces) soup.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  };
  TriangleSoup smallSoup;
  add(smallSoup, shapes::tetrahedron(), Vec3(3, 0, 0), 0.15);
  add(smallSoup, TriangleSoup{{{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0.02}}, {{0, 1, 2}}}, Vec3(0, 3, 0), 1.0);
  TriangleSoup soup{ball.positions(), ball.faces()};
  add(soup, smallSoup, Vec3::Zero(), 1.0);
  const Mesh all = build(soup);
  const int nb = ball.vertexCount();
  REQUIRE(all.vertexCount() == nb + 7);

  const Pieces parts = pieces(all);
  REQUIRE(parts.vertexCount == std::vector<int>{nb, 4, 3});
  REQUIRE(parts.pieceOf[0] == 0);
  REQUIRE(parts.pieceOf[nb] == 1);
  REQUIRE(parts.pieceOf[nb + 6] == 2);

  // Both presets, and the hybrid method (the small pieces are set aside before the wavelet analysis).
  for (auto [preset, levels] : {std::pair{DenoisePreset::Default, 0}, std::pair{DenoisePreset::Paper, 0},
                                std::pair{DenoisePreset::Default, 1}}) {
    INFO((preset == DenoisePreset::Paper ? "paper" : "default") << ", levels " << levels);
    // Every candidate handed out, for the rest with the small pieces and for the ball alone.
    std::vector<std::vector<Vec3>> seenAll, seenAlone;
    DenoiseOptions o, oAlone;
    o.preset = preset;
    o.levels = levels;
    oAlone = o;
    o.onCandidate = [&](int, int, const std::vector<Vec3>& x, double) { seenAll.push_back(x); };
    oAlone.onCandidate = [&](int, int, const std::vector<Vec3>& x, double) { seenAlone.push_back(x); };
    Mesh alone = ball, m = all;
    const DenoiseResult ra = denoise(alone, oAlone), r = denoise(m, o);
    REQUIRE(r.keptPieces == 2);
    REQUIRE(r.keptVertices == 7);
    REQUIRE(ra.keptPieces == 0);
    REQUIRE(r.filteredVertices == ra.filteredVertices);
    // The ball's vertices, bit for bit as if it were alone; the small pieces' untouched.
    for (int v = 0; v < nb; ++v) REQUIRE(m.position(v) == alone.position(v));
    for (int v = nb; v < nb + 7; ++v) REQUIRE(m.position(v) == all.position(v));
    REQUIRE(r.passesRun == ra.passesRun);
    // The candidates come as the caller numbers the whole mesh (with levels, synthesized to it):
    // the ball's part as if alone, the small pieces where they were.
    REQUIRE(seenAll.size() == seenAlone.size());
    if (preset == DenoisePreset::Default) REQUIRE(seenAll.size() > 4);
    for (size_t i = 0; i < seenAll.size(); ++i) {
      REQUIRE(seenAll[i].size() == static_cast<size_t>(all.vertexCount()));
      REQUIRE(seenAlone[i].size() == static_cast<size_t>(nb));
      for (int v = 0; v < nb; ++v) REQUIRE(seenAll[i][v] == seenAlone[i][v]);
      for (int v = nb; v < nb + 7; ++v) REQUIRE(seenAll[i][v] == all.position(v));
    }
  }

  // Denoised with the rest (minPieceVertices 0), the tetrahedron is taken for noise: it shrinks.
  DenoiseOptions every;
  every.minPieceVertices = 0;
  Mesh m = all;
  const DenoiseResult r = denoise(m, every);
  REQUIRE(r.keptPieces == 0);
  auto edge = [](const Mesh& mesh, int v) { return (mesh.position(v) - mesh.position(v + 1)).norm(); };
  INFO("tetrahedron edge " << edge(all, nb) << " -> " << edge(m, nb));
  REQUIRE(edge(m, nb) < 0.8 * edge(all, nb));

  // Nothing but small pieces: nothing moves.
  Mesh small = build(smallSoup);
  const std::vector<Vec3> before = small.positions();
  const DenoiseResult none = denoise(small);
  REQUIRE(none.keptPieces == 2);
  REQUIRE(none.filteredVertices == 0);
  REQUIRE(small.positions() == before);
}

TEST_CASE("denoise rejects bad options and cancels without touching the mesh", "[denoise]") {
  Mesh m = withNoise(build(shapes::icosphere(3)), 0.3, 3);
  const std::vector<Vec3> before = m.positions();
  auto refuses = [&](auto change, const char* what) {
    DenoiseOptions bad;
    change(bad);
    INFO(what);
    REQUIRE_THROWS_AS(denoise(m, bad), InputError);
    REQUIRE(m.positions() == before);
  };
  refuses([](DenoiseOptions& o) { o.strength = 0; }, "strength 0");
  refuses([](DenoiseOptions& o) { o.noiseLevel = -1; }, "negative noise");
  refuses([](DenoiseOptions& o) { o.rangeBandwidths = {0.35, std::nan("")}; }, "NaN h_r");
  refuses([](DenoiseOptions& o) { o.presmoothing.clear(); }, "no presmoothing candidate");
  refuses([](DenoiseOptions& o) { o.neighborhood.radius = 0; }, "radius 0");
  refuses([](DenoiseOptions& o) { o.maxPasses = 0; }, "no passes");
  refuses([](DenoiseOptions& o) { o.impulseShrink = -0.5; }, "negative impulse shrink");
  refuses([](DenoiseOptions& o) { o.impulseKurtosis = std::nan(""); }, "NaN impulse kurtosis");
  refuses([](DenoiseOptions& o) { o.tieProbes = -1; }, "negative tie probes");
  refuses([](DenoiseOptions& o) { o.tieMargin = std::nan(""); }, "NaN tie margin");
  refuses([](DenoiseOptions& o) { o.tieStandardErrors = -1; }, "negative tie standard errors");
  refuses([](DenoiseOptions& o) { o.taubinOnlySteps = {8, 5}; }, "Taubin-only steps descending");
  refuses([](DenoiseOptions& o) { o.taubinOnlySteps = {0, 5}; }, "Taubin-only steps 0");
  refuses([](DenoiseOptions& o) { o.candidateTaubin.mu = -0.4; }, "Taubin-only mu above -lambda");
  refuses([](DenoiseOptions& o) { o.taubinOnlyMargin = -0.01; }, "negative Taubin-only margin");
  refuses([](DenoiseOptions& o) { o.detailBoundRatio = 1.5; }, "detail bound ratio above 1");
  refuses([](DenoiseOptions& o) { o.detailBoundRatio = std::nan(""); }, "NaN detail bound ratio");
  refuses([](DenoiseOptions& o) { o.levelLean = 0; }, "level lean 0");
  refuses([](DenoiseOptions& o) { o.blendSpread = -0.01; }, "negative blend spread");
  refuses([](DenoiseOptions& o) { o.blendSpread = 1001; }, "blend spread beyond 1000");
  refuses([](DenoiseOptions& o) { o.blendSpread = std::nan(""); }, "NaN blend spread");
  refuses([](DenoiseOptions& o) { o.gradientRiskWeight = -0.1; }, "negative gradient risk weight");
  refuses([](DenoiseOptions& o) { o.impulseSpectrumKurtosis = -1; }, "negative impulse spectrum kurtosis");
  refuses([](DenoiseOptions& o) { o.impulseSpectrumMinSamples = -1; }, "negative impulse spectrum minimum samples");
  refuses([](DenoiseOptions& o) { o.planarLevelShare = -0.1; }, "negative planar level share");
  refuses([](DenoiseOptions& o) { o.planarLevelShare = 1.5; }, "planar level share above 1");
  refuses([](DenoiseOptions& o) { o.planarLevelShare = std::nan(""); }, "NaN planar level share");
  refuses([](DenoiseOptions& o) { o.planarKeep = -0.1; }, "negative planar keep");
  refuses([](DenoiseOptions& o) { o.planarKeep = std::nan(""); }, "NaN planar keep");
  refuses([](DenoiseOptions& o) { o.gradientRiskWeight = std::nan(""); }, "NaN gradient risk weight");
  refuses([](DenoiseOptions& o) { o.levelLean = std::nan(""); }, "NaN level lean");
  refuses([](DenoiseOptions& o) { o.minPieceVertices = -1; }, "negative smallest piece");
  refuses([](DenoiseOptions& o) { o.preset = DenoisePreset::Paper, o.paper.passes = 0; }, "paper: no passes");
  refuses([](DenoiseOptions& o) { o.preset = DenoisePreset::Paper, o.paper.meanShift.spatialBandwidth = 0; }, "paper: h_s 0");

  for (DenoisePreset preset : {DenoisePreset::Default, DenoisePreset::Paper}) {
    std::atomic<bool> cancel{false};
    Progress progress;
    progress.cancel = &cancel;
    int reports = 0;
    // Cancel half-way, after vertex updates have moved the working copies.
    progress.report = [&](double f, std::string_view) {
      ++reports;
      if (f > 0.5) cancel = true;
    };
    DenoiseOptions o;
    o.preset = preset;
    o.fixedPasses = preset == DenoisePreset::Default ? 6 : 0;
    REQUIRE_THROWS_AS(denoise(m, o, progress), Cancelled);
    REQUIRE(reports > 0);
    REQUIRE(m.positions() == before);
  }
}

// --- the paper preset ---------------------------------------------------------------------------

// The paper's pipeline with the consensus face-normal rule lands at about 6° of crease error on the
// uniform noise (21° noisy); the paper's own rule (Mean) bevels the edges to about 46°.
TEST_CASE("paper preset: denoising a noisy CAD block halves the error; the paper's face rule bevels", "[denoise][paper]") {
  const Mesh clean = build(shapes::box(12, 12, 12));
  const Mesh noisy = withNoise(clean, 0.5, 3, NoiseDistribution::Uniform);
  const double noisyRms = rmsTo(noisy, clean), noisyEdges = meanFeatureEdgeError(clean, noisy);
  for (RangeUpdate update : {RangeUpdate::Sampled, RangeUpdate::Joint}) {
    Mesh m = noisy;
    DenoiseOptions o;
    o.preset = DenoisePreset::Paper;
    o.paper.meanShift.rangeUpdate = update;
    const DenoiseResult r = denoise(m, o);
    const double after = rmsTo(m, clean), edges = meanFeatureEdgeError(clean, m);
    INFO((update == RangeUpdate::Joint ? "joint" : "sampled") << ": RMS " << noisyRms << " -> " << after
                                                                   << ", crease error " << noisyEdges << " -> " << edges);
    REQUIRE(after < 0.5 * noisyRms);
    REQUIRE(edges < noisyEdges);
    if (update == RangeUpdate::Sampled) REQUIRE(edges < 10);
    REQUIRE(flippedFaces(noisy, m) == 0);  // the paper preset's guard: never, across all passes
    REQUIRE(r.convergedFraction > 0.9);
  }
  Mesh bevelled = noisy;
  DenoiseOptions o;
  o.preset = DenoisePreset::Paper;
  o.paper.faceNormals = FaceNormalRule::Mean;
  denoise(bevelled, o);
  REQUIRE(meanFeatureEdgeError(clean, bevelled) > 30);
}

TEST_CASE("hybrid denoising: the coarse mesh is denoised, the details dropped", "[denoise][hybrid]") {
  const Mesh clean = build(shapes::icosphere(5));
  const Mesh noisy = withNoise(clean, 0.5, 8, NoiseDistribution::Uniform);
  for (DenoisePreset preset : {DenoisePreset::Default, DenoisePreset::Paper}) {
    Mesh m = noisy;
    DenoiseOptions o;
    o.preset = preset;
    o.levels = 2;
    o.alpha = {0};
    const DenoiseResult r = denoise(m, o);
    INFO("RMS " << rmsTo(noisy, clean) << " -> " << rmsTo(m, clean) << " filtering " << r.filteredVertices << " vertices");
    REQUIRE(m.vertexCount() == clean.vertexCount());
    REQUIRE(r.filteredVertices < 0.65 * clean.vertexCount());
    REQUIRE(rmsTo(m, clean) < 0.5 * rmsTo(noisy, clean));
    o.alpha = {0, 0, 0};  // three gains for two levels
    REQUIRE_THROWS_AS(denoise(m, o), InputError);
  }
}

// docs/denoising.md#a-light-start. A ladder of one rung ranks least at its first rung on any mesh,
// which makes the trigger fire where the test wants it.
TEST_CASE("a light start races where the ladder ranks least at its first rung, and its winner must keep its normals calm",
          "[denoise][light-start]") {
  const Mesh clean = build(shapes::icosphere(3));
  const Mesh noisy = withNormalNoise(clean, 0.3, 5);
  DenoiseOptions o;
  o.threads = 1;
  o.blendSpread = 0;  // the result is then one candidate, which can be computed alone
  o.tieProbes = 0;

  // The default ladder ranks least further up: no light start, and the same bits as without one.
  Mesh plain = noisy, off = noisy;
  const DenoiseResult rp = denoise(plain, o);
  REQUIRE_FALSE(rp.lightStartRaced);
  DenoiseOptions none = o;
  none.lightStart = 0;
  denoise(off, none);
  REQUIRE(plain.positions() == off.positions());

  // One rung: the light start races and, its normals turning little, its winner stands. The result
  // is that candidate exactly.
  o.taubinOnlySteps = {200};
  Mesh light = noisy;
  const DenoiseResult rl = denoise(light, o);
  INFO("light: Taubin " << rl.presmoothingSteps << " + " << rl.passes << " passes at h_r " << rl.rangeBandwidth);
  REQUIRE(rl.lightStartRaced);
  REQUIRE_FALSE(rl.lightStartTurnedDown);
  REQUIRE(rl.presmoothingSteps == o.lightStart);
  REQUIRE_FALSE(rl.taubinOnly);
  REQUIRE(light.positions() == candidateAlone(noisy, rl.presmoothingSteps, rl.passes, false, rl.rangeBandwidth, rl.noiseLevel));
  REQUIRE(rmsTo(light, clean) < 0.5 * rmsTo(noisy, clean));
  // Threads change nothing with six runs racing either.
  DenoiseOptions two = o;
  two.threads = 2;
  Mesh lightTwo = noisy;
  denoise(lightTwo, two);
  REQUIRE(lightTwo.positions() == light.positions());

  // A turn no candidate can keep under: the best of the rest wins, and it is that candidate exactly,
  // from another start.
  DenoiseOptions strict = o;
  strict.lightStartTurn = 1e-9;
  Mesh down = noisy;
  const DenoiseResult rd = denoise(down, strict);
  INFO("turned down: Taubin " << rd.presmoothingSteps << " + " << rd.passes << " passes, Taubin only: " << rd.taubinOnly);
  REQUIRE(rd.lightStartRaced);
  REQUIRE(rd.lightStartTurnedDown);
  REQUIRE((rd.taubinOnly || rd.presmoothingSteps != strict.lightStart));
  REQUIRE(down.positions() ==
          candidateAlone(noisy, rd.presmoothingSteps, rd.passes, rd.taubinOnly, rd.rangeBandwidth, rd.noiseLevel));
  REQUIRE(down.positions() != light.positions());

  // Turned down, it takes no part in the tie or the blends either.
  strict.blendSpread = DenoiseOptions{}.blendSpread;
  strict.tieProbes = DenoiseOptions{}.tieProbes;
  strict.tieMargin = 1;  // every start's best contends
  Mesh mixed = noisy;
  const DenoiseResult rm = denoise(mixed, strict);
  REQUIRE(rm.lightStartTurnedDown);
  REQUIRE((rm.taubinOnly || rm.presmoothingSteps != strict.lightStart));
  for (const DenoiseResult::Blend& b : {rm.blend, rm.startBlend})
    if (b.weight > 0) REQUIRE((b.taubinOnly || b.presmoothingSteps != strict.lightStart));

  // Not where the spectrum's tails say impulsive noise, nor where a start of as many steps is
  // offered anyway, nor when switched off.
  Mesh impulsive = clean;
  NoiseOptions spikes;
  spikes.amount = 0.5;
  spikes.distribution = NoiseDistribution::Impulsive;
  spikes.direction = NoiseDirection::Normal;
  spikes.seed = 5;
  addNoise(impulsive, spikes);
  const DenoiseResult ri = denoise(impulsive, o);
  REQUIRE(ri.spectrumKurtosis > o.impulseSpectrumKurtosis);
  REQUIRE_FALSE(ri.lightStartRaced);
  DenoiseOptions listed = o;
  listed.presmoothing = {1, 15};
  Mesh l = noisy;
  REQUIRE_FALSE(denoise(l, listed).lightStartRaced);
  DenoiseOptions zero = o;
  zero.lightStart = 0;
  Mesh z = noisy;
  REQUIRE_FALSE(denoise(z, zero).lightStartRaced);

  // Bad settings are refused before the mesh is touched.
  DenoiseOptions bad = o;
  bad.lightStart = -1;
  Mesh b = noisy;
  REQUIRE_THROWS_AS(denoise(b, bad), InputError);
  bad.lightStart = 1;
  bad.lightStartTurn = 0;
  REQUIRE_THROWS_AS(denoise(b, bad), InputError);
  REQUIRE(b.positions() == noisy.positions());
}

// The default denoiser (denoise.hpp; docs/denoising.md#the-default-pipeline).
//
// Candidates x(k, t): k Taubin steps, then t passes of [blurring mean shift of the face normals →
// vertex update]. For each, Stein's unbiased risk estimate of the error along the vertex normals is
//   SURE = Σ_i ((x_i − y_i)·N_i)² − mσ² + 2σ² div,  div ≈ Σ_i b_i ((x'_i − x_i)·N_i) / ε,
// with y the input, N the vertex normals of y after a few Taubin steps, σ the noise level, and x'
// the same candidate computed from y + ε b N for a random ±1 probe b (Monte-Carlo SURE, Ramani et
// al. 2008). The candidate of least SURE is returned. Every candidate runs on both copies, so the cost is twice the passes computed.
#include <chrono>
#include <cmath>
#include <random>
#include <string>

#include "denoise_detail.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"

namespace geoshift::denoise_detail {

namespace {

void validate(const DenoiseOptions& o) {
  auto bad = [](const std::string& what) { throw InputError("denoise: " + what); };
  if (!(o.noiseLevel >= 0) || !std::isfinite(o.noiseLevel))
    bad("noise level must be >= 0 (0: estimate it; got " + std::to_string(o.noiseLevel) + ")");
  if (!(o.strength > 0) || !std::isfinite(o.strength)) bad("strength must be > 0 (got " + std::to_string(o.strength) + ")");
  if (o.rangeBandwidths.empty()) bad("range bandwidths need at least one candidate h_r");
  for (double hr : o.rangeBandwidths)
    if (!(hr > 0) || !std::isfinite(hr)) bad("range bandwidth h_r must be > 0 (got " + std::to_string(hr) + ")");
  if (o.presmoothing.empty()) bad("presmoothing needs at least one candidate step count");
  for (int k : o.presmoothing)
    if (k < 0 || k > 10000) bad("presmoothing steps must be in [0, 10000] (got " + std::to_string(k) + ")");
  if (o.maxPasses < 1 || o.maxPasses > 10000) bad("maximum passes must be in [1, 10000] (got " + std::to_string(o.maxPasses) + ")");
  if (o.patience < 1) bad("patience must be at least 1 (got " + std::to_string(o.patience) + ")");
  if (o.fixedPasses < 0 || o.fixedPasses > 10000) bad("fixed passes must be in [0, 10000] (got " + std::to_string(o.fixedPasses) + ")");
  if (o.riskNormalSmoothing < 0 || o.riskNormalSmoothing > 10000)
    bad("risk normal smoothing must be in [0, 10000] steps (got " + std::to_string(o.riskNormalSmoothing) + ")");
  if (o.vertexIterations < 1 || o.vertexIterations > 10000)
    bad("vertex iterations must be in [1, 10000] (got " + std::to_string(o.vertexIterations) + ")");
}

// One copy of the mesh being denoised: its positions and the face normals its guard refers to.
struct Track {
  std::vector<Vec3> positions;
  const VertexUpdateOptions* update = nullptr;  // with the reference normals of its start, shared
};

}  // namespace

DenoiseResult denoiseDefault(Mesh& mesh, const DenoiseOptions& o, const Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  validate(o);
  DenoiseResult result;
  result.filteredVertices = mesh.vertexCount();
  result.threads = resolveThreads(o.threads);
  const double ael = averageEdgeLength(mesh);
  double level = o.noiseLevel;
  if (level == 0) {
    level = estimateNoise(mesh).level;
    result.noiseEstimated = true;
  }
  level *= o.strength;
  result.noiseLevel = level;
  auto finish = [&] {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  if (!(level > 0)) return finish();  // nothing to remove
  const double sigma = level * ael;
  const int n = mesh.vertexCount();
  const std::vector<Vec3> input = mesh.positions();
  // The passes run on `mesh` itself (below): on an exception it gets its input back. assign() into a
  // vector of the same size does not allocate, so the restore cannot throw.
  struct Restore {
    Mesh& mesh;
    const std::vector<Vec3>& input;
    bool armed = true;
    ~Restore() {
      if (armed) mesh.positions().assign(input.begin(), input.end());
    }
  } restore{mesh, input};
  ParallelOptions parallel;
  parallel.threads = o.threads;

  // Neighbourhoods on a smoothed support, found once.
  progress.step(0, "support");
  FaceNeighborhoodOptions hoodOptions = o.neighborhood;
  hoodOptions.parallel.threads = o.threads;
  FaceNeighborhoods hoods;
  {
    Mesh support = mesh;
    taubinSmooth(support, o.supportSmoothing);
    hoods = faceNeighborhoods(support, hoodOptions, progress.slice(0, 0.1));
  }
  result.neighborhoodBytes = hoods.bytes();

  // The passes use `mesh` for its connectivity, with each track's positions swapped in and out (a
  // copy would cost 50 bytes a vertex); the chosen positions go back into it at the end.
  Mesh& work = mesh;
  auto presmooth = [&](Track& t, int steps) {
    if (steps == 0) return;
    TaubinOptions taubin = o.supportSmoothing;
    taubin.iterations = steps;
    work.positions() = t.positions;
    taubinSmooth(work, taubin);
    t.positions = work.positions();
  };
  auto pass = [&](Track& t, double rangeBandwidth) {
    work.positions() = t.positions;
    std::vector<Vec3> targets = shiftFaceNormals(hoods, faceAreas(work), faceNormals(work), rangeBandwidth, parallel);
    VertexUpdateResult u = updateVertices(work, std::move(targets), *t.update);
    result.limitedSteps += u.limitedSteps;
    t.positions = std::move(u.positions);
    ++result.passesRun;
  };
  // Vertex update options per start (input, probe), each holding its start's face normals as the
  // flip guard's reference, shared by every candidate and pass.
  auto updateFrom = [&](const std::vector<Vec3>& start) {
    VertexUpdateOptions update;
    update.iterations = o.vertexIterations;
    update.flipGuard = FlipGuard::InputOrTarget;
    update.parallel = parallel;
    work.positions() = start;
    update.referenceNormals = referenceNormalsOf(work);
    return update;
  };
  const VertexUpdateOptions inputUpdate = updateFrom(input);

  if (o.fixedPasses > 0) {
    const double hr = o.rangeBandwidths.front();
    Track x{input, &inputUpdate};
    presmooth(x, o.presmoothing.front());
    for (int t = 1; t <= o.fixedPasses; ++t) {
      progress.step(0.1 + 0.9 * (t - 1) / o.fixedPasses, "denoise passes");
      pass(x, hr);
    }
    result.presmoothingSteps = o.presmoothing.front();
    result.rangeBandwidth = hr;
    result.passes = o.fixedPasses;
    mesh.positions() = std::move(x.positions);
    restore.armed = false;
    return finish();
  }

  // The probe: ±1 per vertex with a normal, from a generator the standard specifies bit for bit.
  // The directions the error is measured along: normals of a lightly smoothed copy of the input.
  std::vector<Vec3> normals;
  if (o.riskNormalSmoothing > 0) {
    TaubinOptions taubin = o.supportSmoothing;
    taubin.iterations = o.riskNormalSmoothing;
    work.positions() = input;
    taubinSmooth(work, taubin);
    normals = vertexNormals(work);
  } else {
    work.positions() = input;
    normals = vertexNormals(work);
  }
  const double eps = 0.01 * sigma;
  std::vector<double> probe(n, 0);
  int m = 0;
  {
    std::mt19937_64 rng(o.seed);
    for (int v = 0; v < n; ++v) {
      const double sign = (rng() >> 63) ? 1.0 : -1.0;
      if (normals[v].squaredNorm() > 0) {
        probe[v] = sign;
        ++m;
      }
    }
  }
  std::vector<Vec3> perturbed = input;
  for (int v = 0; v < n; ++v) perturbed[v] += eps * probe[v] * normals[v];
  const VertexUpdateOptions perturbedUpdate = updateFrom(perturbed);

  // SURE with the noise level times the strength (what candidates are ranked by), and with the noise
  // level alone (the unbiased estimate of the error that is reported).
  struct Risk {
    double ranked, unbiased;
  };
  const double sigma1 = sigma / o.strength;
  auto risk = [&](const Track& x, const Track& xp) {
    double fit = 0, div = 0;
    for (int v = 0; v < n; ++v) {
      if (probe[v] == 0) continue;
      const double d = (x.positions[v] - input[v]).dot(normals[v]);
      fit += d * d;
      div += probe[v] * (xp.positions[v] - x.positions[v]).dot(normals[v]);
    }
    div /= eps;
    const double count = std::max(1, m);
    return Risk{(fit - m * sigma * sigma + 2 * sigma * sigma * div) / count,
                (fit - m * sigma1 * sigma1 + 2 * sigma1 * sigma1 * div) / count};
  };

  // The candidates race in step, one pass each in turn. A candidate stops after `patience` passes
  // that did not lower its risk by 0.2% of the noise variance (on smooth shapes the risk keeps
  // creeping down for dozens of passes by less), and, once it has run `patience` passes, as soon as
  // its best risk is 2% of the noise variance above the leader's: it is not going to catch up, and
  // the passes it would have run are half the cost on meshes where one candidate clearly fits.
  struct Run {
    int steps;
    double rangeBandwidth;
    Track x, xp;
    int t = 0, lastBest = 0;
    double anchor = 0;  // the risk at the last pass that lowered it by more than the tolerance
    double best = 0;
    bool active = true;
  };
  std::vector<Vec3> best;
  Risk bestRisk{0, 0};
  auto score = [&](Run& run) {
    const Risk r = risk(run.x, run.xp);
    if (run.t == 0 || r.ranked < run.anchor - 0.002 * sigma * sigma) {
      run.anchor = r.ranked;
      run.lastBest = run.t;
    }
    if (run.t == 0 || r.ranked < run.best) run.best = r.ranked;
    if (best.empty() || r.ranked < bestRisk.ranked) {
      bestRisk = r;
      best = run.x.positions;
      result.presmoothingSteps = run.steps;
      result.rangeBandwidth = run.rangeBandwidth;
      result.passes = run.t;
    }
  };
  std::vector<Run> runs;
  for (int steps : o.presmoothing) {
    for (double hr : o.rangeBandwidths) {
      runs.push_back({steps, hr, {input, &inputUpdate}, {perturbed, &perturbedUpdate}});
      Run& run = runs.back();
      presmooth(run.x, steps);
      presmooth(run.xp, steps);
      score(run);
    }
  }
  std::vector<Vec3>().swap(perturbed);  // the probe tracks have started from it
  const double total = static_cast<double>(runs.size()) * o.maxPasses;
  for (int done = 0;;) {
    bool any = false;
    for (Run& run : runs) {
      if (!run.active) continue;
      progress.step(0.1 + 0.9 * std::min(1.0, done / total), "denoise passes");
      pass(run.x, run.rangeBandwidth);
      pass(run.xp, run.rangeBandwidth);
      ++run.t;
      ++done;
      score(run);
      if (run.t - run.lastBest >= o.patience || run.t >= o.maxPasses) run.active = false;
      any = any || run.active;
    }
    if (!any) break;
    double leader = runs.front().best;
    for (const Run& run : runs) leader = std::min(leader, run.best);
    for (Run& run : runs)
      if (run.active && run.t >= o.patience && run.best > leader + 0.02 * sigma * sigma) run.active = false;
  }
  result.estimatedError = std::sqrt(std::max(0.0, bestRisk.unbiased)) / ael;
  mesh.positions() = std::move(best);
  restore.armed = false;
  return finish();
}

}  // namespace geoshift::denoise_detail

// op "denoise": vertex positions denoised as `geoshift denoise` does it (cli/denoise.cpp): method
// "meanshift" (the default; preset "default" or "paper", docs/denoising.md), "bilateral" (Zheng et
// al.) or "taubin" (a baseline).
#include <string>
#include <vector>

#include "geoshift/bilateral_normal.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/error.hpp"
#include "geoshift/smoothing.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

namespace {

// Parameters that belong to one method only; given with another method they are an error, not
// silently ignored (a user who sets h_s for Taubin smoothing expects it to matter).
struct MethodParams {
  const char* method;
  std::vector<const char*> names;
};

const std::vector<MethodParams>& methodParams() {
  static const std::vector<MethodParams> table = {
      {"meanshift", {"preset", "noise", "strength", "hs", "hr", "radius", "kmax", "eps", "passes", "rangeUpdate",
                     "faceNormals", "threads", "supportIterations"}},
      {"bilateral", {"normalIterations", "sigmaC", "sigmaS", "neighbors"}},
      {"taubin", {"iterations", "lambda", "mu"}},
  };
  return table;
}

void rejectOtherMethodsParams(const Params& p, const std::string& method) {
  for (const MethodParams& m : methodParams()) {
    if (m.method == method) continue;
    for (const char* name : m.names)
      if (p.has(name))
        throw InputError(std::string("denoise: parameter ") + name + " belongs to method \"" + m.method +
                         "\", not \"" + method + "\"");
  }
  if (method == "taubin" && p.has("vertexIterations"))
    throw InputError("denoise: parameter vertexIterations does not apply to method \"taubin\"");
}

// Parameters of one mean shift preset only, refused with the other (as the CLI does).
void rejectOtherPresetsParams(const Params& p, const std::string& preset) {
  const std::vector<const char*> defaultOnly = {"noise", "strength"};
  const std::vector<const char*> paperOnly = {"kmax", "eps", "rangeUpdate", "faceNormals", "supportIterations"};
  for (const char* name : preset == "paper" ? defaultOnly : paperOnly)
    if (p.has(name))
      throw InputError(std::string("denoise: parameter ") + name + " does not apply to preset \"" + preset + "\"");
}

}  // namespace

OpOutput runDenoise(const OpContext& context) {
  const Params& p = context.params;
  const std::string method = p.choice("method", "meanshift", {"meanshift", "bilateral", "taubin"});
  rejectOtherMethodsParams(p, method);
  // levels > 0: the hybrid denoiser (denoise a wavelet-coarsened mesh, add the details back times
  // alpha), for the mean shift only, as in the CLI.
  const int levels = p.integer("levels", 0, 0, 64);
  const double alpha = p.number("alpha", 0, -100, 100);
  if (levels > 0 && method != "meanshift")
    throw InputError("denoise: wavelet levels apply to method \"meanshift\" only");

  Mesh mesh = context.session.build.mesh;
  OpOutput out;
  out.stats.set("method", method);
  if (method == "meanshift") {
    DenoiseOptions o;
    o.levels = levels;
    o.alpha = {alpha};
    const std::string preset = p.choice("preset", "default", {"default", "paper"});
    rejectOtherPresetsParams(p, preset);
    const int threads = context.threads(p.integer("threads", 0, 0, 1024));
    out.stats.set("preset", preset);
    if (preset == "paper") {
      o.preset = DenoisePreset::Paper;
      PaperDenoiseOptions& paper = o.paper;
      MeanShiftOptions& ms = paper.meanShift;
      paper.passes = p.integer("passes", paper.passes, 1, 10000);
      ms.spatialBandwidth = p.number("hs", ms.spatialBandwidth, 1e-6, 1e6);
      ms.rangeBandwidth = p.number("hr", ms.rangeBandwidth, 1e-12, 1e12);
      ms.radius = p.number("radius", ms.radius, 0, 1e6);
      ms.maxIterations = p.integer("kmax", ms.maxIterations, 1, 1000000);
      ms.epsilon = p.number("eps", ms.epsilon, 1e-9, 1e6);
      // Defaults are the core's (the paper's sampled update, the consensus face rule), as in the CLI.
      if (p.has("rangeUpdate"))
        ms.rangeUpdate = p.choice("rangeUpdate", "sampled", {"joint", "sampled"}) == "sampled" ? RangeUpdate::Sampled
                                                                                               : RangeUpdate::Joint;
      if (p.has("faceNormals"))
        paper.faceNormals = p.choice("faceNormals", "consensus", {"consensus", "mean"}) == "mean"
                                ? FaceNormalRule::Mean
                                : FaceNormalRule::Consensus;
      ms.parallel.threads = threads;
      paper.support.iterations = p.integer("supportIterations", paper.support.iterations, 0, 1000000);
      paper.vertexUpdate.iterations = p.integer("vertexIterations", paper.vertexUpdate.iterations, 0, 1000000);
      const DenoiseResult r = denoise(mesh, o, context.progress);
      out.stats.set("passes", paper.passes);
      out.stats.set("meanIterations", r.meanIterations);
      out.stats.set("convergedFraction", r.convergedFraction);
      out.stats.set("limitedSteps", r.limitedSteps);
      out.stats.set("threads", r.threads);
      out.stats.set("ms", r.seconds * 1000);
    } else {
      o.noiseLevel = p.number("noise", 0, 0, 1e6);
      o.strength = p.number("strength", 1, 1e-6, 1e6);
      if (p.has("hr")) o.rangeBandwidths = {p.number("hr", o.rangeBandwidths.front(), 1e-6, 1e6)};
      o.neighborhood.spatialBandwidth = p.number("hs", o.neighborhood.spatialBandwidth, 1e-6, 1e6);
      o.neighborhood.radius = p.number("radius", o.neighborhood.radius, 1e-6, 1e6);
      o.fixedPasses = p.integer("passes", 0, 0, 10000);  // 0: chosen by SURE
      o.vertexIterations = p.integer("vertexIterations", o.vertexIterations, 1, 1000000);
      o.threads = threads;
      const DenoiseResult r = denoise(mesh, o, context.progress);
      out.stats.set("noiseLevel", r.noiseLevel);
      out.stats.set("noiseEstimated", r.noiseEstimated ? "yes" : "no");
      out.stats.set("presmoothingSteps", r.presmoothingSteps);
      out.stats.set("passes", r.passes);
      out.stats.set("passesRun", r.passesRun);
      out.stats.set("estimatedError", r.estimatedError);
      out.stats.set("limitedSteps", r.limitedSteps);
      out.stats.set("threads", r.threads);
      out.stats.set("ms", r.seconds * 1000);
    }
  } else if (method == "bilateral") {
    BilateralNormalOptions o;
    o.normalIterations = p.integer("normalIterations", o.normalIterations, 0, 1000000);
    o.sigmaSpatial = p.number("sigmaC", o.sigmaSpatial, 0, 1e6);
    o.sigmaRange = p.number("sigmaS", o.sigmaRange, 1e-12, 1e6);
    o.neighborhood = p.choice("neighbors", "vertex", {"vertex", "edge"}) == "edge" ? FaceNeighborhood::Edge
                                                                                   : FaceNeighborhood::Vertex;
    o.vertexUpdate.iterations = p.integer("vertexIterations", o.vertexUpdate.iterations, 0, 1000000);
    const BilateralNormalResult r = bilateralNormalDenoise(mesh, o, context.progress);
    out.stats.set("iterations", o.normalIterations);
    out.stats.set("limitedSteps", r.vertexUpdate.limitedSteps);
    out.stats.set("threads", 1);
  } else {
    TaubinOptions o;
    o.iterations = p.integer("iterations", o.iterations, 0, 1000000);
    o.lambda = p.number("lambda", o.lambda, -10, 10);
    o.mu = p.number("mu", o.mu, -10, 10);
    taubinSmooth(mesh, o, context.progress);
    out.stats.set("iterations", o.iterations);
    out.stats.set("threads", 1);
  }
  out.positions = mesh.positions();
  return out;
}

}  // namespace geoshift::wasm

// What a denoise request means (denoise_request.hpp).
#include "geoshift/denoise_request.hpp"

#include <string>
#include <vector>

#include "geoshift/error.hpp"

namespace geoshift {

namespace {

void applyVertexUpdate(const ParamRequest& r, VertexUpdateOptions& o) {
  if (r.has("vertexIterations")) o.iterations = r.integer("vertexIterations");
  if (r.has("fixedBoundary")) o.fixedBoundary = r.flag("fixedBoundary");
  if (r.has("flipGuard")) o.flipGuard = r.text("flipGuard") == "input-or-target" ? FlipGuard::InputOrTarget : FlipGuard::Input;
}

void applyPaper(const ParamRequest& r, DenoiseOptions& o) {
  PaperDenoiseOptions& p = o.paper;
  MeanShiftOptions& ms = p.meanShift;
  if (r.has("hs")) ms.spatialBandwidth = r.number("hs");
  if (r.has("hr")) {
    const std::vector<double> hr = r.numbers("hr");
    if (hr.size() != 1)
      throw InputError("denoise: parameter hr takes one value with preset \"paper\" (got " + std::to_string(hr.size()) + ")");
    if (!(hr.front() > 0)) throw InputError("denoise: parameter hr must be > 0 with preset \"paper\" (got 0)");
    ms.rangeBandwidth = hr.front();
  }
  if (r.has("radius")) ms.radius = r.number("radius");
  if (r.has("passes")) p.passes = r.integer("passes");
  if (r.has("kmax")) ms.maxIterations = r.integer("kmax");
  if (r.has("eps")) ms.epsilon = r.number("eps");
  if (r.has("rangeUpdate")) ms.rangeUpdate = r.text("rangeUpdate") == "joint" ? RangeUpdate::Joint : RangeUpdate::Sampled;
  if (r.has("faceNormals")) p.faceNormals = r.text("faceNormals") == "mean" ? FaceNormalRule::Mean : FaceNormalRule::Consensus;
  if (r.has("supportIterations")) p.support.iterations = r.integer("supportIterations");
  if (r.has("exactCharts")) ms.tuning.exactCharts = r.flag("exactCharts");
  if (r.has("doubleWeights")) ms.tuning.singlePrecisionKernel = !r.flag("doubleWeights");
  if (r.has("threads")) ms.parallel.threads = r.integer("threads");
  applyVertexUpdate(r, p.vertexUpdate);
}

void applyDefault(const ParamRequest& r, DenoiseOptions& o) {
  if (r.has("noise")) o.noiseLevel = r.number("noise");
  if (r.has("strength")) o.strength = r.number("strength");
  if (r.has("hs")) o.neighborhood.spatialBandwidth = r.number("hs");
  // hr 0 (alone): the default candidates, as noise 0 and passes 0 leave their choice to the denoiser.
  if (r.has("hr") && r.numbers("hr") != std::vector<double>{0.0}) o.rangeBandwidths = r.numbers("hr");
  if (r.has("radius")) o.neighborhood.radius = r.number("radius");
  if (r.has("passes")) o.fixedPasses = r.integer("passes");
  if (r.has("presmoothing")) {
    o.presmoothing.clear();
    for (double k : r.numbers("presmoothing")) o.presmoothing.push_back(static_cast<int>(k));
  }
  if (r.has("taubinOnly")) {
    // 0 (alone): no Taubin-only candidate; a 0 among others is refused by the denoiser.
    const std::vector<double> steps = r.numbers("taubinOnly");
    o.taubinOnlySteps.clear();
    if (steps != std::vector<double>{0.0})
      for (double k : steps) o.taubinOnlySteps.push_back(static_cast<int>(k));
  }
  if (r.has("lightStart")) o.lightStart = r.integer("lightStart");
  if (r.has("impulse")) {
    const std::string rule = r.text("impulse");
    if (rule == "off") o.impulseShrink = 0;
    if (rule == "on") o.impulseKurtosis = 0;
  }
  if (r.has("maxPasses")) o.maxPasses = r.integer("maxPasses");
  if (r.has("patience")) o.patience = r.integer("patience");
  if (r.has("seed")) o.seed = static_cast<std::uint64_t>(r.integer64("seed"));
  if (r.has("vertexIterations")) o.vertexIterations = r.integer("vertexIterations");
}

}  // namespace

const char* denoiseMethodName(DenoiseMethod method) {
  switch (method) {
    case DenoiseMethod::MeanShift:
      return "meanshift";
    case DenoiseMethod::Bilateral:
      return "bilateral";
    case DenoiseMethod::Taubin:
      return "taubin";
  }
  return "?";
}

DenoiseSettings denoiseSettings(const ParamRequest& r, DenoiseSettings s) {
  const std::string method = r.text("method");
  if (method == "bilateral") {
    s.method = DenoiseMethod::Bilateral;
    BilateralNormalOptions& o = s.bilateral;
    if (r.has("normalIterations")) o.normalIterations = r.integer("normalIterations");
    if (r.has("sigmaC")) o.sigmaSpatial = r.number("sigmaC");
    if (r.has("sigmaS")) o.sigmaRange = r.number("sigmaS");
    if (r.has("neighbors")) o.neighborhood = r.text("neighbors") == "edge" ? FaceNeighborhood::Edge : FaceNeighborhood::Vertex;
    applyVertexUpdate(r, o.vertexUpdate);
  } else if (method == "taubin") {
    s.method = DenoiseMethod::Taubin;
    TaubinOptions& o = s.taubin;
    if (r.has("iterations")) o.iterations = r.integer("iterations");
    if (r.has("lambda")) o.lambda = r.number("lambda");
    if (r.has("mu")) o.mu = r.number("mu");
    if (r.has("threads")) o.parallel.threads = r.integer("threads");
  } else {
    s.method = DenoiseMethod::MeanShift;
    DenoiseOptions& o = s.meanShift;
    o.preset = r.text("preset") == "paper" ? DenoisePreset::Paper : DenoisePreset::Default;
    if (r.has("threads")) o.threads = r.integer("threads");
    if (r.has("levels")) o.levels = r.integer("levels");
    if (r.has("alpha")) o.alpha = r.numbers("alpha");
    if (r.has("minPiece")) o.minPieceVertices = r.integer("minPiece");
    if (o.preset == DenoisePreset::Paper)
      applyPaper(r, o);
    else
      applyDefault(r, o);
  }
  return s;
}

DenoiseSettings denoiseSettings(ParamValues given, DenoiseSettings base) {
  return denoiseSettings(ParamRequest(paramSpecsOf("denoise"), std::move(given)), std::move(base));
}

}  // namespace geoshift

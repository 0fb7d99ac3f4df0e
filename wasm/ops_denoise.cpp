// op "denoise": vertex positions denoised as `geoshift denoise` does it: method "meanshift" (the
// default; preset "default" or "paper", docs/denoising.md), "bilateral" (Zheng et al.) or "taubin"
// (a baseline). What the request means, its defaults and ranges are the core's
// (denoise_request.hpp), shared with the CLI and Python.
#include "geoshift/denoise_request.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runDenoise(const OpContext& context) {
  DenoiseSettings settings = denoiseSettings(context.params);
  Mesh mesh = context.session.build.mesh;
  OpOutput out;
  out.stats.set("method", std::string(denoiseMethodName(settings.method)));
  if (settings.method == DenoiseMethod::MeanShift) {
    DenoiseOptions& o = settings.meanShift;
    o.threads = context.threads(o.threads);
    o.paper.meanShift.parallel.threads = o.threads;
    const DenoiseResult r = denoise(mesh, o, context.progress);
    if (o.preset == DenoisePreset::Paper) {
      out.stats.set("preset", std::string("paper"));
      out.stats.set("passes", o.paper.passes);
      out.stats.set("meanIterations", r.meanIterations);
      out.stats.set("convergedFraction", r.convergedFraction);
    } else {
      out.stats.set("preset", std::string("default"));
      out.stats.set("noiseLevel", r.noiseLevel);
      out.stats.set("noiseEstimated", r.noiseEstimated ? "yes" : "no");
      out.stats.set("presmoothingSteps", r.presmoothingSteps);
      out.stats.set("passes", r.passes);
      out.stats.set("taubinOnly", r.taubinOnly ? "yes" : "no");
      out.stats.set("rangeBandwidth", r.rangeBandwidth);
      out.stats.set("passesRun", r.passesRun);
      out.stats.set("tieProbes", r.tieProbes);
      out.stats.set("tieByNormals", r.tieByNormals ? "yes" : "no");
      // docs/denoising.md#a-light-start
      out.stats.set("lightStart", r.lightStartTurnedDown ? "turned down" : r.lightStartRaced ? "raced" : "no");
      out.stats.set("estimatedError", r.estimatedError);
      out.stats.set("impulseGarrote", r.impulseGarrote ? "yes" : "no");
      // docs/denoising.md#the-noise-level ("Planes left untouched") and #impulsive-noise ("Vertices
      // on untouched planes")
      out.stats.set("planarLevel", r.planarLevel ? "yes" : "no");
      out.stats.set("planarKept", r.planarKept);
      out.stats.set("keptInput", r.keptInput ? "yes" : "no");
      out.stats.set("blendWeight", r.blend.weight);
      out.stats.set("blendSteps", r.blend.presmoothingSteps);
      out.stats.set("blendPasses", r.blend.passes);
      out.stats.set("blendTaubinOnly", r.blend.taubinOnly ? "yes" : "no");
      out.stats.set("blendRangeBandwidth", r.blend.rangeBandwidth);
      out.stats.set("startBlendWeight", r.startBlend.weight);
      out.stats.set("startBlendSteps", r.startBlend.presmoothingSteps);
      out.stats.set("startBlendPasses", r.startBlend.passes);
      out.stats.set("startBlendRangeBandwidth", r.startBlend.rangeBandwidth);
      out.stats.set("displacementKurtosis", r.displacementKurtosis);
      out.stats.set("spectrumKurtosis", r.spectrumKurtosis);
    }
    out.stats.set("keptPieces", r.keptPieces);
    out.stats.set("keptVertices", r.keptVertices);
    out.stats.set("limitedSteps", r.limitedSteps);
    out.stats.set("threads", r.threads);
    out.stats.set("ms", r.seconds * 1000);
  } else if (settings.method == DenoiseMethod::Bilateral) {
    const BilateralNormalResult r = bilateralNormalDenoise(mesh, settings.bilateral, context.progress);
    out.stats.set("iterations", settings.bilateral.normalIterations);
    out.stats.set("limitedSteps", r.vertexUpdate.limitedSteps);
    out.stats.set("threads", 1);
  } else {
    settings.taubin.parallel.threads = context.threads(settings.taubin.parallel.threads);
    taubinSmooth(mesh, settings.taubin, context.progress);
    out.stats.set("iterations", settings.taubin.iterations);
    out.stats.set("threads", settings.taubin.parallel.threads);
  }
  out.positions = mesh.positions();
  return out;
}

}  // namespace geoshift::wasm

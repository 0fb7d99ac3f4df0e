// denoise(): the hybrid wrapper and the choice of pipeline (denoise.hpp).
#include "geoshift/denoise.hpp"

#include <chrono>
#include <string>

#include "denoise_detail.hpp"
#include "geoshift/error.hpp"

namespace geoshift {

namespace {

DenoiseResult direct(Mesh& mesh, const DenoiseOptions& options, const Progress& progress) {
  if (mesh.faceCount() == 0) throw InputError("denoise: the mesh has no faces");
  return options.preset == DenoisePreset::Paper ? denoise_detail::denoisePaper(mesh, options, progress)
                                                : denoise_detail::denoiseDefault(mesh, options, progress);
}

}  // namespace

DenoiseResult denoise(Mesh& mesh, const DenoiseOptions& options, const Progress& progress) {
  if (options.levels < 0) throw InputError("denoise: levels must be >= 0 (got " + std::to_string(options.levels) + ")");
  if (options.levels == 0) return direct(mesh, options, progress);
  const auto start = std::chrono::steady_clock::now();
  WaveletOptions w = options.wavelet;
  w.levels = options.levels;
  const Multiresolution mr = analyze(mesh, AttributeSet(mesh.vertexCount()), w, progress.slice(0, 0.05));
  Mesh coarse = mr.coarse;
  DenoiseOptions flat = options;
  flat.levels = 0;
  DenoiseResult result = direct(coarse, flat, progress.slice(0.05, 0.95));
  const SynthesisResult fine = synthesize(mr, coarse.positions(), mr.coarseAttributes, options.alpha, progress.slice(0.95, 1));
  mesh.positions() = fine.mesh.positions();
  result.filteredVertices = coarse.vertexCount();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geoshift

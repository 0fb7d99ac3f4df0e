// denoise(): small pieces set aside, the hybrid wrapper and the choice of pipeline (denoise.hpp).
#include "geoshift/denoise.hpp"

#include <chrono>
#include <string>
#include <vector>

#include "denoise_detail.hpp"
#include "geoshift/error.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/parallel.hpp"

namespace geoshift {

namespace {

DenoiseResult preset(Mesh& mesh, const DenoiseOptions& options, const Progress& progress) {
  return options.preset == DenoisePreset::Paper ? denoise_detail::denoisePaper(mesh, options, progress)
                                                : denoise_detail::denoiseDefault(mesh, options, progress);
}

// The preset, or with levels > 0 the preset on the coarse mesh of a wavelet analysis, the details
// restored times alpha (Algorithm 2 on positions).
DenoiseResult hybridOrPreset(Mesh& mesh, const DenoiseOptions& options, const Progress& progress) {
  if (options.levels == 0) return preset(mesh, options, progress);
  const auto start = std::chrono::steady_clock::now();
  WaveletOptions w = options.wavelet;
  w.levels = options.levels;
  const Multiresolution mr = analyze(mesh, AttributeSet(mesh.vertexCount()), w, progress.slice(0, 0.05));
  Mesh coarse = mr.coarse;
  // Candidates are handed out as the fine mesh they would give, each synthesized from its coarse one.
  DenoiseOptions coarseOptions = options;
  if (options.onCandidate)
    coarseOptions.onCandidate = [&](int steps, int passes, const std::vector<Vec3>& x, double risk) {
      options.onCandidate(steps, passes, synthesize(mr, x, mr.coarseAttributes, options.alpha).mesh.positions(), risk);
    };
  DenoiseResult result = preset(coarse, coarseOptions, progress.slice(0.05, 0.95));
  const SynthesisResult fine = synthesize(mr, coarse.positions(), mr.coarseAttributes, options.alpha, progress.slice(0.95, 1));
  mesh.positions() = fine.mesh.positions();
  result.filteredVertices = coarse.vertexCount();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

// The pieces of at least minPieceVertices vertices are denoised as a mesh of their own (vertices and
// faces in their order, so a mesh with no small piece is denoised exactly as before); the small
// pieces of the mesh given keep their positions, with the hybrid method too (docs/denoising.md#small-pieces).
DenoiseResult denoise(Mesh& mesh, const DenoiseOptions& options, const Progress& progress) {
  if (options.levels < 0) throw InputError("denoise: levels must be >= 0 (got " + std::to_string(options.levels) + ")");
  if (options.minPieceVertices < 0)
    throw InputError("denoise: the smallest piece denoised must be >= 0 vertices (got " +
                     std::to_string(options.minPieceVertices) + ")");
  if (mesh.faceCount() == 0) throw InputError("denoise: the mesh has no faces");
  Pieces parts = pieces(mesh);
  std::vector<char> small(parts.vertexCount.size(), 0);
  int keptPieces = 0, keptVertices = 0;
  for (size_t p = 0; p < small.size(); ++p) {
    if (parts.vertexCount[p] >= options.minPieceVertices) continue;
    small[p] = 1;
    ++keptPieces;
    keptVertices += parts.vertexCount[p];
  }
  if (keptPieces == 0) {
    parts = {};  // not held through the denoise (docs/denoising.md#speed-and-memory)
    return hybridOrPreset(mesh, options, progress);
  }

  std::vector<int> restIndex(mesh.vertexCount(), -1);
  std::vector<Vec3> positions;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    if (parts.pieceOf[v] >= 0 && small[parts.pieceOf[v]]) continue;
    restIndex[v] = static_cast<int>(positions.size());
    positions.push_back(mesh.position(v));
  }
  std::vector<Face> faces;
  for (const Face& f : mesh.faces())
    if (!small[parts.pieceOf[f[0]]]) faces.push_back({restIndex[f[0]], restIndex[f[1]], restIndex[f[2]]});
  DenoiseResult result;
  if (!faces.empty()) {
    Mesh rest(std::move(positions), faces);
    // The rest's positions back into the caller's numbering; the small pieces keep theirs.
    auto putBack = [&](std::vector<Vec3>& into, const std::vector<Vec3>& ofRest) {
      for (int v = 0; v < mesh.vertexCount(); ++v)
        if (restIndex[v] >= 0) into[v] = ofRest[restIndex[v]];
    };
    // Candidates are handed out the same way, as the whole mesh.
    DenoiseOptions restOptions = options;
    if (options.onCandidate)
      restOptions.onCandidate = [&](int steps, int passes, const std::vector<Vec3>& x, double risk) {
        std::vector<Vec3> full = mesh.positions();
        putBack(full, x);
        options.onCandidate(steps, passes, full, risk);
      };
    result = hybridOrPreset(rest, restOptions, progress);
    putBack(mesh.positions(), rest.positions());
  } else {
    result.threads = resolveThreads(options.threads);
  }
  result.keptPieces = keptPieces;
  result.keptVertices = keptVertices;
  return result;
}

}  // namespace geoshift

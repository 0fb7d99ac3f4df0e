// geoshift denoise: remove noise from vertex positions, keeping sharp features. Its options are the
// parameters of the core's denoise table (params.hpp; their help and defaults come from there) and
// what they mean is the core's (denoise_request.hpp), as for the wasm op and Python: a parameter of
// another method or preset is refused with the message they give.
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "geoshift/denoise_request.hpp"
#include "geoshift/error.hpp"

namespace geoshift::cli {
namespace {

struct DenoiseArgs {
  std::string in, out;
  std::optional<TableOptions> options;  // the denoise request's parameters
};

// docs/denoising.md#small-pieces
std::string keptPieces(const DenoiseResult& r, const DenoiseOptions& o) {
  if (r.keptPieces == 0) return "";
  std::ostringstream s;
  s << r.keptPieces << (r.keptPieces == 1 ? " piece" : " pieces") << " of fewer than " << o.minPieceVertices
    << " vertices (" << r.keptVertices << " vertices) kept as " << (r.keptPieces == 1 ? "it was" : "they were")
    << " (--min-piece)";
  return s.str();
}

void runMeanShift(Mesh& mesh, const DenoiseOptions& o) {
  const DenoiseResult r = denoise(mesh, o);
  if (r.keptPieces > 0 && r.filteredVertices == 0) {
    std::cerr << "geoshift: nothing denoised: " << keptPieces(r, o) << "\n";
    return;
  }
  if (r.keptPieces > 0) std::cerr << "geoshift: " << keptPieces(r, o) << "\n";
  if (o.preset == DenoisePreset::Paper) {
    std::cerr << "geoshift: mean shift (paper preset) " << o.paper.passes << " passes, iterations mean " << r.meanIterations
              << ", converged " << 100 * r.convergedFraction << "%, " << r.threads << " threads\n";
    return;
  }
  std::ostringstream line;
  line.precision(3);
  // docs/denoising.md#the-noise-level ("Planes left untouched")
  line << "geoshift: noise level " << r.noiseLevel << " AEL"
       << (r.noiseEstimated ? (r.planarLevel ? " (estimated from the mesh, against the planes the noise left" : " (estimated from the mesh")
                            : " (given")
       << (o.strength != 1 ? ", times strength " : "");
  if (o.strength != 1) line << o.strength;
  line << "); ";
  if (!(r.noiseLevel > 0)) {
    line << "nothing to remove";
  } else if (r.keptInput) {
    // docs/denoising.md#the-input-as-a-candidate
    line << "kept as it was: no candidate is estimated closer to the noise-free surface than the input ("
         << r.passesRun << " passes computed)";
  } else if (o.fixedPasses > 0) {
    line << "Taubin " << r.presmoothingSteps << " steps + " << r.passes << " mean shift passes (fixed)";
  } else {
    // docs/denoising.md#taubin-only-candidates
    if (r.taubinOnly)
      line << "Taubin " << r.presmoothingSteps << " steps (mu " << o.candidateTaubin.mu << "), no mean shift pass,";
    else
      line << "Taubin " << r.presmoothingSteps << " steps + " << r.passes << " mean shift passes at h_r " << r.rangeBandwidth;
    line << " chosen by SURE (estimated error ";
    // The unbiased estimate can come out below zero when the result is much closer to the truth
    // than the noise; that is below what one probe resolves (docs/denoising.md).
    if (r.estimatedError > 0)
      line << r.estimatedError << " AEL";
    else
      line << "too small to resolve";
    line << ", " << r.passesRun << " passes computed";
    // docs/denoising.md#ties-between-starts
    if (r.tieProbes > 0)
      line << ", a tie between starts settled by " << r.tieProbes << " more probe" << (r.tieProbes > 1 ? "s" : "")
           << (r.tieByNormals ? " and the normals' turn" : "");
    line << ")";
    // docs/denoising.md#the-blend-of-least-risk
    auto blended = [&](const char* lead, const DenoiseResult::Blend& b) {
      if (b.weight <= 0) return;
      line << lead;
      if (b.taubinOnly)
        line << "Taubin " << b.presmoothingSteps << " steps alone";
      else
        line << "Taubin " << b.presmoothingSteps << " steps + " << b.passes << " passes at h_r " << b.rangeBandwidth;
      line << " (its weight " << b.weight << ")";
    };
    blended(", blended with ", r.blend);
    blended(r.blend.weight > 0 ? ", then with " : ", blended with ", r.startBlend);
    // docs/denoising.md#a-light-start
    if (r.lightStartRaced)
      line << (r.lightStartTurnedDown ? "; a light start of " + std::to_string(o.lightStart) + " Taubin step(s) raced, its winner turned down (its normals turned too much)"
                                      : "; a light start of " + std::to_string(o.lightStart) + " Taubin step(s) raced (the ladder ranked least at its first rung)");
    // docs/denoising.md#impulsive-noise
    if (r.impulseGarrote)
      line << (o.impulseKurtosis > 0 ? "; the noise looks impulsive: outliers" : "; outliers (--impulse on)")
           << " corrected, the other vertices mostly kept (kurtosis " << r.displacementKurtosis << " of the displacement, "
           << r.spectrumKurtosis << " of the highest frequencies)";
    // docs/denoising.md#impulsive-noise ("Vertices on untouched planes")
    if (r.planarKept == 1) line << "; 1 vertex on an untouched plane kept at its input position";
    else if (r.planarKept > 1) line << "; " << r.planarKept << " vertices on untouched planes kept at their input positions";
  }
  line << ", " << r.threads << (r.threads == 1 ? " thread" : " threads");
  // docs/denoising.md#speed-and-memory (spatial order)
  if (r.spatialOrder)
    line << ", run in spatial order (" << 100 * r.farAdjacencies << "% of the file's adjacencies lie far apart in it)";
  std::cerr << line.str() << "\n";
}

void runMethod(Mesh& mesh, const DenoiseSettings& s) {
  switch (s.method) {
    case DenoiseMethod::MeanShift:
      runMeanShift(mesh, s.meanShift);
      return;
    case DenoiseMethod::Bilateral:
      bilateralNormalDenoise(mesh, s.bilateral);
      return;
    case DenoiseMethod::Taubin:
      taubinSmooth(mesh, s.taubin);
      return;
  }
}

}  // namespace

Command addDenoise(CLI::App& app) {
  auto a = std::make_shared<DenoiseArgs>();
  CLI::App* sub = app.add_subcommand("denoise", "Remove noise from vertex positions, keeping sharp features");
  sub->add_option("IN", a->in, "input mesh (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("-o,--output", a->out, "output mesh; format from its extension")->required();
  a->options.emplace(sub, "denoise");

  return {sub, [a] {
            const DenoiseSettings settings = denoiseSettings(a->options->request());
            const auto start = std::chrono::steady_clock::now();
            Document doc = load(a->in);
            long vertices = 0;
            double filterSeconds = 0;
            for (MeshPart& part : doc.parts) {
              MeshBuild b = buildPart(doc, part);
              // Every position of the part is written back from the mesh (each file vertex has a
              // mesh vertex), so the part's own copy is not held through the denoise (24 bytes a
              // vertex of the peak: docs/denoising.md#speed-and-memory). On an error nothing is written.
              const size_t count = part.positions.size();
              std::vector<Vec3>().swap(part.positions);
              const auto t0 = std::chrono::steady_clock::now();
              runMethod(b.mesh, settings);
              filterSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
              vertices += b.mesh.vertexCount();
              part.positions.resize(count);
              writeBack(part, b);
            }
            save(doc, a->out);
            const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cerr << "geoshift: denoise " << denoiseMethodName(settings.method) << ": " << vertices << " vertices in "
                      << doc.parts.size() << (doc.parts.size() == 1 ? " part" : " parts") << ", filter "
                      << static_cast<long>(filterSeconds * 1000 + 0.5) << " ms, total "
                      << static_cast<long>(total * 1000 + 0.5) << " ms -> " << a->out << "\n";
          }};
}

}  // namespace geoshift::cli

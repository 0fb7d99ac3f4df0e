// geoshift wavelet: multiresolution smoothing (alpha < 1) or enhancement (alpha > 1) of the positions
// and vertex colors of every part, by lifting analysis to L levels and synthesis with detail gains.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "geoshift/error.hpp"
#include "geoshift/requests.hpp"

namespace geoshift::cli {
namespace {

struct Args {
  std::string in, out;
  std::optional<TableOptions> options;  // the wavelet op's parameters, checked as the wasm op checks them
};

// Analyses and synthesises one part; returns the vertex counts per level.
std::vector<int> processPart(MeshPart& part, MeshBuild& b, const WaveletRequest& a) {
  AttributeSet signals(b.mesh.vertexCount());
  std::vector<double> before;  // welded colors, to hand back only the change (seams keep their split)
  const bool colors = !part.colors.empty() && !a.positionsOnly;
  if (colors) {
    std::vector<double> rgb(part.colors.size() * 3);
    for (size_t i = 0; i < part.colors.size(); ++i)
      for (int c = 0; c < 3; ++c) rgb[3 * i + c] = part.colors[i][c];
    before = toMeshLayout(rgb, 3, b.vertexOf, b.mesh);
    signals.set("color", 3, AttributeKind::Euclidean, before);
  }
  const Multiresolution mr = analyze(b.mesh, signals, a.options);
  const SynthesisResult r = synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, a.alpha);
  b.mesh.positions() = r.mesh.positions();
  writeBack(part, b);
  if (colors) {
    const std::vector<double>& after = r.attributes.get("color").values;
    for (size_t i = 0; i < part.colors.size(); ++i) {
      const int v = b.vertexOf[i];
      // Colors are stored in [0, 1]; enhancement can overshoot.
      for (int c = 0; c < 3; ++c)
        part.colors[i][c] = std::clamp(part.colors[i][c] + after[3 * v + c] - before[3 * v + c], 0.0, 1.0);
    }
  }
  return mr.vertexCounts();
}

std::string joined(const std::vector<int>& counts) {
  std::ostringstream s;
  for (size_t i = 0; i < counts.size(); ++i) s << (i ? " -> " : "") << counts[i];
  return s.str();
}

}  // namespace

Command addWavelet(CLI::App& app) {
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "wavelet", "Multiresolution smoothing/enhancement of positions and colors (lifting wavelets, detail gains alpha)");
  sub->add_option("IN", a->in, "input mesh (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("-o,--output", a->out, "output mesh; format from its extension")->required();
  a->options.emplace(sub, "wavelet");
  return {sub, [a] {
            const WaveletRequest w = waveletRequest(a->options->request());
            if (w.alpha.size() != 1 && w.alpha.size() != static_cast<size_t>(w.options.levels))
              throw InputError("--alpha has " + std::to_string(w.alpha.size()) + " values for " +
                               std::to_string(w.options.levels) + " levels; give one value or one per level");
            const auto start = std::chrono::steady_clock::now();
            Document doc = load(a->in);
            for (MeshPart& part : doc.parts) {
              MeshBuild b = buildPart(doc, part);
              const std::vector<int> counts = processPart(part, b, w);
              std::cerr << "geoshift: wavelet " << part.label << ": vertices per level " << joined(counts) << "\n";
              if (static_cast<int>(counts.size()) - 1 < w.options.levels)
                std::cerr << "geoshift: note: " << part.label << ": only " << counts.size() - 1
                          << " level(s) possible; the remaining gains are unused\n";
            }
            save(doc, a->out);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cerr << "geoshift: wavelet " << w.options.levels << " level(s) in " << seconds << " s -> " << a->out << "\n";
          }};
}

}  // namespace geoshift::cli

// geoshift wavelet: multiresolution smoothing (alpha < 1) or enhancement (alpha > 1) of the positions
// and vertex colors of every part, by lifting analysis to L levels and synthesis with detail gains.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "geoshift/error.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift::cli {
namespace {

struct Args {
  std::string in, out;
  int levels = 2;
  std::vector<double> alpha = {0.0};
  bool positionsOnly = false;
};

// Analyses and synthesises one part; returns the vertex counts per level.
std::vector<int> processPart(MeshPart& part, MeshBuild& b, const Args& a) {
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
  WaveletOptions o;
  o.levels = a.levels;
  const Multiresolution mr = analyze(b.mesh, signals, o);
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
  sub->add_option("--levels", a->levels, "analysis levels (each removes ~25% of the vertices)")
      ->capture_default_str();
  sub->add_option("--alpha", a->alpha,
                  "detail gain: one value for all levels or one per level, finest first "
                  "(0 removes the details, 1 keeps them, > 1 enhances)")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_flag("--positions-only", a->positionsOnly, "leave vertex colors as they are");
  return {sub, [a] {
            if (a->levels < 0) throw InputError("--levels must be >= 0 (got " + std::to_string(a->levels) + ")");
            if (a->alpha.size() != 1 && a->alpha.size() != static_cast<size_t>(a->levels))
              throw InputError("--alpha has " + std::to_string(a->alpha.size()) + " values for " +
                               std::to_string(a->levels) + " levels; give one value or one per level");
            for (double v : a->alpha)
              if (!std::isfinite(v)) throw InputError("--alpha values must be finite numbers");
            const auto start = std::chrono::steady_clock::now();
            Document doc = load(a->in);
            for (MeshPart& part : doc.parts) {
              MeshBuild b = buildPart(doc, part);
              const std::vector<int> counts = processPart(part, b, *a);
              std::cerr << "geoshift: wavelet " << part.label << ": vertices per level " << joined(counts) << "\n";
              if (static_cast<int>(counts.size()) - 1 < a->levels)
                std::cerr << "geoshift: note: " << part.label << ": only " << counts.size() - 1
                          << " level(s) possible; the remaining gains are unused\n";
            }
            save(doc, a->out);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cerr << "geoshift: wavelet " << a->levels << " level(s) in " << seconds << " s -> " << a->out << "\n";
          }};
}

}  // namespace geoshift::cli

// geoshift filter: Riemannian mean shift / blurring mean shift of a vertex signal of every part.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "filter_signal.hpp"
#include "geoshift/error.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/presets.hpp"

namespace geoshift::cli {

namespace {

struct FilterArgs {
  std::string in, out, preset;
  std::optional<TableOptions> options;  // the filter op's parameters, checked as the wasm op checks them
  bool exactCharts = false, doubleWeights = false;
};

// The preset (if any), then every option given on the command line over it (filterRequest).
FilterSettings settingsOf(const FilterArgs& a) {
  const FilterRequest r = filterRequest(a.options->request(), a.preset.empty() ? nullptr : &filterPreset(a.preset));
  FilterSettings s;
  s.signal = r.signal;
  s.options = r.options;
  s.rangeGiven = r.rangeBandwidth.has_value();
  s.hybrid = r.hybrid;
  s.options.tuning.exactCharts = a.exactCharts;
  s.options.tuning.singlePrecisionKernel = !a.doubleWeights;
  return s;
}

}  // namespace

Command addFilter(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "filter", "Riemannian mean shift (--mode ms) or blurring mean shift (--mode bms) of a vertex signal");
  auto a = std::make_shared<FilterArgs>();
  sub->add_option("IN", a->in, "input mesh (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("-o,--output", a->out, "output mesh; format from its extension")->required();
  sub->add_option("--preset", a->preset, "color, curvature-ms, curvature-bms, terrain-ms, terrain-bms (paper §4.2)");
  std::vector<std::pair<std::string, std::string>> notes;
  for (const char* name : {"signal", "passes", "hs", "hr", "radius", "kmax", "eps", "rangeUpdate", "levels", "alpha"})
    notes.emplace_back(name, "or the preset's");
  a->options.emplace(sub, "filter", std::vector<std::string>{}, notes);
  sub->add_flag("--exact-charts", a->exactCharts, "a fresh log map at every iteration (slower reference)");
  sub->add_flag("--double-weights", a->doubleWeights,
                "kernel weights in double precision (slower; single precision moves outputs by ~1e-7 of the signal's scale)");
  return {sub, [a] {
            const FilterSettings settings = settingsOf(*a);
            Document doc = load(a->in);
            FilterSummary total;
            // Parts without the signal (a label mesh beside a colored one) are left as they are,
            // as long as one part has it.
            std::vector<std::string> skipped;
            for (const MeshPart& part : doc.parts)
              if (std::string why = missingSignal(doc, part, settings); !why.empty()) skipped.push_back(why);
            if (skipped.size() == doc.parts.size()) throw InputError(skipped.front() + "; choose another --signal");
            for (const std::string& why : skipped) std::cerr << "geoshift: skipped: " << why << "\n";
            for (MeshPart& part : doc.parts) {
              if (!missingSignal(doc, part, settings).empty()) continue;
              const MeshBuild b = buildPart(doc, part);
              const HybridResult r = filterPart(doc, part, b, settings);
              total.add(r.coarse, r.vertexCounts.back());
            }
            save(doc, a->out);
            std::printf("filter: %d vertices, iterations mean %.2f max %d, converged %.1f%%, %.3f s, %d threads\n",
                        total.vertices, total.meanIterations(), total.maxIterations, 100 * total.convergedFraction(),
                        total.seconds, total.threads);
          }};
}

}  // namespace geoshift::cli

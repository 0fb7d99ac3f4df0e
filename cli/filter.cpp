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
  std::string in, out, signal, mode, preset, rangeUpdate;
  std::optional<double> hs, hr, radius, eps;
  std::optional<int> kmax, passes, levels;
  std::vector<double> alpha;
  bool filterGeometry = false;
  int threads = 0;
  bool segments = false, exactCharts = false, doubleWeights = false;
};

// The preset (if any), then every option given on the command line over it.
FilterSettings settingsOf(const FilterArgs& a) {
  FilterSettings s;
  if (!a.preset.empty()) {
    const FilterPreset& p = filterPreset(a.preset);
    s.options = p.options;
    s.signal = p.signal;
    s.rangeGiven = true;
    s.hybrid.levels = p.levels;
    s.hybrid.alpha = {p.detailGain};
  }
  if (!a.signal.empty()) s.signal = a.signal;
  if (s.signal.empty()) s.signal = "color";
  MeanShiftOptions& o = s.options;
  o.passes = filterPasses(a.mode, a.passes, o.passes);
  if (a.hs) o.spatialBandwidth = *a.hs;
  if (a.hr) {
    o.rangeBandwidth = *a.hr;
    s.rangeGiven = true;
  }
  if (a.radius) o.radius = *a.radius;
  if (a.eps) o.epsilon = *a.eps;
  if (a.kmax) o.maxIterations = *a.kmax;
  if (a.rangeUpdate == "sampled") o.rangeUpdate = RangeUpdate::Sampled;
  if (a.rangeUpdate == "joint") o.rangeUpdate = RangeUpdate::Joint;
  if (a.levels) s.hybrid.levels = *a.levels;
  if (!a.alpha.empty()) s.hybrid.alpha = a.alpha;
  s.hybrid.filterGeometry = a.filterGeometry;
  o.tuning.exactCharts = a.exactCharts;
  o.tuning.singlePrecisionKernel = !a.doubleWeights;
  o.segments = a.segments;
  o.parallel.threads = a.threads;
  return s;
}

}  // namespace

Command addFilter(CLI::App& app) {
  auto a = std::make_shared<FilterArgs>();
  CLI::App* sub = app.add_subcommand(
      "filter", "Riemannian mean shift (--mode ms) or blurring mean shift (--mode bms) of a vertex signal");
  sub->add_option("IN", a->in, "input mesh (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("-o,--output", a->out, "output mesh; format from its extension")->required();
  sub->add_option("--signal", a->signal,
                  "color (COLOR_0), normal (vertex normals), curvature (absolute), terrain (height above ground "
                  "and class), or the name of a float attribute such as _HEIGHT; several names separated by commas "
                  "are filtered together (default: color, or the preset's)");
  sub->add_option("--preset", a->preset, "color, curvature-ms, curvature-bms, terrain-ms, terrain-bms (paper §4.2)");
  sub->add_option("--mode", a->mode, "ms = one pass (mean shift), bms = blurring passes (default 10)")
      ->check(CLI::IsMember({"ms", "bms"}));
  sub->add_option("--passes", a->passes, "number of passes (bms)");
  sub->add_option("--hs", a->hs, "spatial bandwidth h_s in multiples of the average edge length (default 3)");
  sub->add_option("--hr", a->hr,
                  "range bandwidth h_r in the signal's units (default: color 0.1, normal 0.45, otherwise a tenth "
                  "of the signal's 10-90% spread)");
  sub->add_option("--radius", a->radius, "truncation radius r in AEL (default 3 h_s)");
  sub->add_option("--kmax", a->kmax, "most iterations per pass (default 50)");
  sub->add_option("--eps", a->eps, "stop when a step is shorter than this, in AEL (default 0.2)");
  sub->add_option("--range-update", a->rangeUpdate,
                  "joint (default): the range value moves with its own mean shift step; sampled (the paper): it "
                  "is read from the signal at the iterate")
      ->check(CLI::IsMember({"sampled", "joint"}));
  sub->add_option("--threads", a->threads, "worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  sub->add_option("--levels", a->levels,
                  "wavelet levels: filter a coarse approximation and restore the details (Algorithm 2; default 0, "
                  "or the preset's)");
  sub->add_option("--alpha", a->alpha, "detail gain per level, finest first, or one for all: 1 restores the "
                                       "details, 0 drops them, > 1 enhances (default 0, or the preset's)")
      ->delimiter(',');
  sub->add_flag("--filter-geometry", a->filterGeometry, "with --levels: the gains apply to the positions too");
  sub->add_flag("--segments", a->segments, "also label vertices by their modes: attribute _SEGMENT");
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

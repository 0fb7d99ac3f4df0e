// op "filter": Riemannian mean shift (mode "ms") or blurring mean shift ("bms") of a vertex signal,
// directly or on a wavelet-coarsened mesh (levels > 0, Algorithm 2), as `geoshift filter` does it (cli/filter.cpp, cli/filter_signal.cpp): the same signals, the same
// default range bandwidths and the same write-back, so both give the same numbers.
#include <algorithm>
#include <cctype>
#include <sstream>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/hybrid.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

namespace {

bool sameIgnoringCase(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// A signal of the session by name: as the CLI finds glTF attributes (the name or "_" + name), and
// then ignoring case, because three.js lower-cases the custom attributes it reads from glTF.
const Attribute* findSignal(const Session& s, const std::string& name) {
  for (const std::string& candidate : {name, "_" + name})
    if (const Attribute* a = s.attributes.find(candidate)) return a;
  for (const Attribute& a : s.attributes.all())
    if (sameIgnoringCase(a.name, name) || sameIgnoringCase(a.name, "_" + name)) return &a;
  return nullptr;
}

std::string signalList(const Session& s) {
  std::string known;
  for (const Attribute& a : s.attributes.all())
    if (a.name != "color" && a.name != "normal") known += (known.empty() ? "" : ", ") + a.name;
  return known.empty() ? "none" : known;
}

// "terrain" stands for the height attribute the terrain command writes and the class, as in the CLI.
std::vector<std::string> expandTerrain(const Session& s, std::vector<std::string> names) {
  if (names.size() != 1 || names[0] != "terrain") return names;
  names.clear();
  for (const char* candidate : {"_HEIGHT_ABOVE_GROUND", "_VEGETATION_HEIGHT"})
    if (findSignal(s, candidate)) {
      names.push_back(candidate);
      break;
    }
  if (findSignal(s, "_CLASS")) names.push_back("_CLASS");
  if (names.empty())
    throw InputError("filter: the mesh has no terrain attribute (_HEIGHT_ABOVE_GROUND, _VEGETATION_HEIGHT or _CLASS); "
                     "set one with setAttribute, or name the attribute in signal");
  return names;
}

struct Source {
  enum Kind { Color, Normal, Curvature, Named } kind;
  std::string name;  // in the filtered set and in the output
};

}  // namespace

OpOutput runFilter(const OpContext& context) {
  const Params& p = context.params;
  const Session& s = context.session;
  const Mesh& mesh = s.build.mesh;

  // levels > 0: the hybrid filter (Algorithm 2), the mean shift on a wavelet-coarsened mesh with
  // the details added back times alpha; 0 is the plain mean shift, as in the CLI.
  HybridOptions hybrid;
  hybrid.levels = p.integer("levels", 0, 0, 64);
  hybrid.alpha = {p.number("alpha", 0, -100, 100)};
  hybrid.filterGeometry = p.flag("filterGeometry", false);

  MeanShiftOptions o;
  // Without a mode, passes alone decides (the CLI's behaviour when --mode is left out).
  const std::string mode = p.has("mode") ? p.choice("mode", "ms", {"ms", "bms"}) : "";
  const bool passesGiven = p.has("passes");
  o.passes = p.integer("passes", 1, 1, 10000);
  if (mode == "bms" && !passesGiven) o.passes = 10;
  if (mode == "ms" && o.passes != 1) throw InputError("filter: mode \"ms\" runs one pass; use mode \"bms\" for passes > 1");
  o.spatialBandwidth = p.number("hs", o.spatialBandwidth, 1e-6, 1e6);
  o.radius = p.number("radius", o.radius, 0, 1e6);
  o.epsilon = p.number("eps", o.epsilon, 1e-9, 1e6);
  o.maxIterations = p.integer("kmax", o.maxIterations, 1, 1000000);
  o.rangeUpdate = p.choice("rangeUpdate", "joint", {"joint", "sampled"}) == "sampled" ? RangeUpdate::Sampled
                                                                                        : RangeUpdate::Joint;
  o.segments = p.flag("segments", false);
  o.parallel.threads = context.threads(p.integer("threads", 0, 0, 1024));
  const bool rangeGiven = p.has("hr");
  const double hr = p.number("hr", 0.1, 1e-12, 1e12);

  std::vector<std::string> names = expandTerrain(s, splitSignalNames(p.text("signal", "color")));
  if (names.empty()) throw InputError("filter: parameter signal names no attribute");

  AttributeSet set(mesh.vertexCount());
  std::vector<Source> sources;
  for (const std::string& name : names) {
    double defaultHr = 0;
    RangeKernel kernel = RangeKernel::Gaussian;
    if (name == "color") {
      const Attribute* color = s.attributes.find("color");
      if (!color) throw InputError("filter: the mesh has no vertex colors; load it with colors, or choose signal normal, curvature or an attribute");
      set.set("COLOR", 3, AttributeKind::Euclidean, color->values);
      sources.push_back({Source::Color, "COLOR"});
      defaultHr = 0.1;
    } else if (name == "normal") {
      // From the geometry, as the CLI does (a file's own normals may be split at hard edges).
      std::vector<double> flat;
      flat.reserve(3 * mesh.vertexCount());
      for (const Vec3& v : vertexNormals(mesh)) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
      set.set("NORMAL", 3, AttributeKind::UnitVector, std::move(flat));
      sources.push_back({Source::Normal, "NORMAL"});
      kernel = RangeKernel::NormalSimilarity;
      defaultHr = 0.45;
    } else if (name == "curvature") {
      context.progress.step(0, "curvature");
      std::vector<double> k = curvatures(mesh).get(CurvatureKind::Absolute);
      defaultHr = spreadBandwidth(k, 1);
      set.set("_CURVATURE", 1, AttributeKind::Euclidean, std::move(k));
      sources.push_back({Source::Curvature, "_CURVATURE"});
    } else {
      const Attribute* a = findSignal(s, name);
      if (!a)
        throw InputError("filter: the mesh has no attribute '" + name + "' (it has: " + signalList(s) +
                         "; or use color, normal, curvature)");
      if (a->dim != 1)
        throw InputError("filter: attribute '" + a->name + "' has " + std::to_string(a->dim) +
                         " numbers per vertex; this op filters one-number attributes (and color, normal)");
      if (set.contains(a->name)) throw InputError("filter: attribute '" + a->name + "' is named twice in signal");
      defaultHr = spreadBandwidth(a->values, 1);
      set.set(a->name, 1, AttributeKind::Euclidean, a->values);
      sources.push_back({Source::Named, a->name});
    }
    o.channels.push_back({sources.back().name, rangeGiven ? hr : defaultHr, kernel});
  }

  HybridResult r = hybridMeanShift(mesh, set, o, hybrid, context.progress);

  OpOutput out;
  if (hybrid.filterGeometry) out.positions = std::move(r.positions);
  for (const Source& source : sources) {
    std::vector<double> values = r.signal.get(source.name).values;
    switch (source.kind) {
      case Source::Color:
        out.colors = std::move(values);
        out.colorsAreSignal = true;
        break;
      case Source::Normal:
        out.normals = std::move(values);
        break;
      case Source::Curvature: {
        // The CLI maps colors over the caller's vertices (its percentiles count every welded copy).
        const std::vector<int>& vertexOf = s.build.vertexOf;
        const std::vector<double> rgb = colorMap(toCallerLayout(values, 1, vertexOf));
        std::vector<double> meshRgb(3 * values.size(), 0.0);
        for (std::size_t i = 0; i < vertexOf.size(); ++i)
          for (int c = 0; c < 3; ++c) meshRgb[3 * vertexOf[i] + c] = rgb[3 * i + c];
        if (!out.colorsAreSignal) out.colors = std::move(meshRgb);
        out.scalars.emplace_back(source.name, std::move(values));
        break;
      }
      case Source::Named:
        out.scalars.emplace_back(source.name, std::move(values));
        break;
    }
  }
  if (o.segments) {
    out.scalars.emplace_back("_SEGMENT", std::vector<double>(r.segment.begin(), r.segment.end()));
    out.stats.set("segmentCount", r.segmentCount);
  }
  out.stats.set("signal", p.text("signal", "color"));
  out.stats.set("passes", o.passes);
  out.stats.set("rangeBandwidth", o.channels.front().rangeBandwidth);
  // Iterations are those of the mean shift, on the coarse mesh when levels > 0.
  out.stats.set("levels", hybrid.levels);
  out.stats.set("filteredVertices", r.vertexCounts.empty() ? mesh.vertexCount() : r.vertexCounts.back());
  out.stats.set("meanIterations", r.coarse.meanIterations);
  out.stats.set("maxIterations", r.coarse.maxIterations);
  out.stats.set("convergedFraction", r.coarse.convergedFraction);
  out.stats.set("threads", r.coarse.threads);
  out.stats.set("ms", r.seconds * 1000);
  return out;
}

}  // namespace geoshift::wasm

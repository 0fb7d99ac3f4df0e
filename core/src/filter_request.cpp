// What a filter request means (filter_request.hpp; docs/algorithms.md#filter-requests).
#include "geoshift/filter_request.hpp"

#include <algorithm>
#include <cctype>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/presets.hpp"

namespace geoshift {

namespace {

bool sameIgnoringCase(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

bool builtIn(const std::string& name) {
  return name == "color" || name == "normal" || name == "curvature" || name == "terrain";
}

const char* const kTerrainHeights[] = {"_HEIGHT_ABOVE_GROUND", "_VEGETATION_HEIGHT"};
const std::string kTerrainMissing =
    " has no terrain attribute (_HEIGHT_ABOVE_GROUND, _VEGETATION_HEIGHT or _CLASS); name the attribute in the signal";

// "terrain" alone: the height attribute the terrain readers write and the class.
std::vector<std::string> expandTerrain(const SignalInputs& in, std::vector<std::string> names) {
  if (names.size() != 1 || names[0] != "terrain") return names;
  names.clear();
  for (const char* candidate : kTerrainHeights)
    if (!findSignalName(in.attributeNames, candidate).empty()) {
      names.push_back(candidate);
      break;
    }
  if (!findSignalName(in.attributeNames, "_CLASS").empty()) names.push_back("_CLASS");
  if (names.empty()) throw InputError(in.where + kTerrainMissing);
  return names;
}

std::string knownAttributes(const SignalInputs& in) {
  std::string known;
  for (const std::string& name : in.attributeNames) known += (known.empty() ? "" : ", ") + name;
  return known.empty() ? "none" : known;
}

}  // namespace

std::string findSignalName(const std::vector<std::string>& available, const std::string& name) {
  for (const std::string& candidate : {name, "_" + name})
    if (std::find(available.begin(), available.end(), candidate) != available.end()) return candidate;
  for (const std::string& a : available)
    if (sameIgnoringCase(a, name) || sameIgnoringCase(a, "_" + name)) return a;
  return "";
}

std::string missingSignal(const std::string& signal, const SignalInputs& in) {
  for (const std::string& name : splitSignalNames(signal)) {
    if (name == "color" && !in.colors) return in.where + " has no vertex colors (COLOR_0)";
    if (name == "terrain" && findSignalName(in.attributeNames, kTerrainHeights[0]).empty() &&
        findSignalName(in.attributeNames, kTerrainHeights[1]).empty() && findSignalName(in.attributeNames, "_CLASS").empty())
      return in.where + kTerrainMissing;
    if (!builtIn(name) && findSignalName(in.attributeNames, name).empty())
      return in.where + " has no attribute '" + name + "' (it has: " + knownAttributes(in) + ")";
  }
  return "";
}

FilterSignal filterSignal(const Mesh& mesh, const std::string& signal, const SignalInputs& in,
                          std::optional<double> rangeBandwidth, const Progress& progress) {
  const std::vector<std::string> names = expandTerrain(in, splitSignalNames(signal));
  if (names.empty()) throw InputError("the signal '" + signal + "' names no attribute");
  FilterSignal out;
  out.values = AttributeSet(mesh.vertexCount());
  for (const std::string& name : names) {
    double hr = 0;
    RangeKernel kernel = RangeKernel::Gaussian;
    std::string channel;
    SignalSource source;
    if (name == "color") {
      if (!in.colors)
        throw InputError(in.where + " has no vertex colors (COLOR_0); choose the signal normal, curvature or an attribute");
      channel = "COLOR";
      out.values.set(channel, 3, AttributeKind::Euclidean, in.colors());
      source = SignalSource::Color;
      hr = kColorRangeBandwidth;
    } else if (name == "normal") {
      // From the geometry: a file's own normals may be split at hard edges.
      std::vector<double> flat;
      flat.reserve(3 * static_cast<size_t>(mesh.vertexCount()));
      for (const Vec3& v : vertexNormals(mesh)) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
      channel = "NORMAL";
      out.values.set(channel, 3, AttributeKind::UnitVector, std::move(flat));
      source = SignalSource::Normal;
      kernel = RangeKernel::NormalSimilarity;
      hr = kNormalRangeBandwidth;
    } else if (name == "curvature") {
      progress.step(0, "curvature");
      std::vector<double> k = curvatures(mesh).get(CurvatureKind::Absolute);
      hr = spreadBandwidth(k, 1);
      channel = "_CURVATURE";
      out.values.set(channel, 1, AttributeKind::Euclidean, std::move(k));
      source = SignalSource::Curvature;
    } else {
      channel = findSignalName(in.attributeNames, name);
      if (channel.empty())
        throw InputError(in.where + " has no attribute '" + name + "' (it has: " + knownAttributes(in) +
                         "; or use color, normal, curvature)");
      if (out.values.contains(channel)) throw InputError("attribute '" + channel + "' is named twice in the signal");
      Attribute a = in.attribute(channel);
      hr = spreadBandwidth(a.values, a.dim);
      out.values.set(channel, a.dim, a.kind, std::move(a.values));
      source = SignalSource::Attribute;
    }
    out.channels.push_back({channel, rangeBandwidth.value_or(hr), kernel});
    out.sources.push_back(source);
  }
  return out;
}

int filterPasses(std::string_view mode, std::optional<int> passes, int base) {
  if (mode == "ms") {
    if (passes && *passes != 1) throw InputError("mode \"ms\" runs one pass; use mode \"bms\" for more passes");
    return 1;
  }
  if (mode == "bms") return passes ? *passes : base == 1 ? 10 : base;
  if (!mode.empty()) throw InputError("mode \"" + std::string(mode) + "\" is neither \"ms\" nor \"bms\"");
  return passes ? *passes : base;
}

FilterRequest filterRequest(const ParamRequest& r, const FilterPreset* preset) {
  FilterRequest f;
  MeanShiftOptions& o = f.options;
  if (preset) {
    o = preset->options;
    f.signal = preset->signal;
    f.rangeBandwidth = o.rangeBandwidth;
    f.hybrid.levels = preset->levels;
    f.hybrid.alpha = {preset->detailGain};
  }
  if (!preset || r.has("signal")) f.signal = r.text("signal");
  try {
    o.passes = filterPasses(r.has("mode") ? r.text("mode") : "", r.has("passes") ? r.optionalInteger("passes") : std::nullopt,
                            o.passes);
  } catch (const InputError& e) {
    throw InputError(std::string("filter: ") + e.what());
  }
  if (r.has("hs")) o.spatialBandwidth = r.number("hs");
  if (r.has("hr")) f.rangeBandwidth = o.rangeBandwidth = r.number("hr");
  if (r.has("radius")) o.radius = r.number("radius");
  if (r.has("eps")) o.epsilon = r.number("eps");
  if (r.has("kmax")) o.maxIterations = r.integer("kmax");
  if (r.has("rangeUpdate")) o.rangeUpdate = r.text("rangeUpdate") == "sampled" ? RangeUpdate::Sampled : RangeUpdate::Joint;
  o.segments = r.flag("segments");
  o.parallel.threads = r.integer("threads");
  if (r.has("levels")) f.hybrid.levels = r.integer("levels");
  if (r.has("alpha")) f.hybrid.alpha = r.numbers("alpha");
  f.hybrid.filterGeometry = r.flag("filterGeometry");
  return f;
}

}  // namespace geoshift

#include "filter_signal.hpp"

#include <algorithm>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift::cli {

namespace {

const ExtraAttribute* findExtra(const MeshPart& part, const std::string& name) {
  for (const ExtraAttribute& e : part.extras)
    if (e.name == name || e.name == "_" + name) return &e;
  return nullptr;
}

struct Source {
  std::string kind;  // color, normal, curvature, extra
  std::string name;  // attribute name in the set (and of the extra)
};

}  // namespace

void FilterSummary::add(const MeanShiftResult& r, int n) {
  vertices += n;
  iterationSum += r.meanIterations * n;
  convergedSum += r.convergedFraction * n;
  maxIterations = std::max(maxIterations, r.maxIterations);
  seconds += r.seconds;
  threads = r.threads;
}

std::string missingSignal(const Document& doc, const MeshPart& part, const FilterSettings& settings) {
  for (const std::string& name : splitSignalNames(settings.signal)) {
    if (name == "color" && part.colors.empty()) return doc.path + ": " + part.label + " has no vertex colors (COLOR_0)";
    if (name == "terrain" && !findExtra(part, "_HEIGHT_ABOVE_GROUND") && !findExtra(part, "_VEGETATION_HEIGHT") &&
        !findExtra(part, "_CLASS"))
      return doc.path + ": " + part.label + " has no terrain attribute (_HEIGHT_ABOVE_GROUND, _VEGETATION_HEIGHT, _CLASS)";
    if (name != "color" && name != "normal" && name != "curvature" && name != "terrain" && !findExtra(part, name))
      return doc.path + ": " + part.label + " has no attribute '" + name + "'";
  }
  return "";
}

HybridResult filterPart(const Document& doc, MeshPart& part, const MeshBuild& build, const FilterSettings& settings) {
  const Mesh& mesh = build.mesh;
  const int n = mesh.vertexCount();
  const std::string where = doc.path + ": " + part.label;
  AttributeSet set(n);
  MeanShiftOptions options = settings.options;
  options.channels.clear();
  std::vector<Source> sources;

  std::vector<std::string> names = splitSignalNames(settings.signal);
  if (names.size() == 1 && names[0] == "terrain") {
    names.clear();
    for (const char* candidate : {"_HEIGHT_ABOVE_GROUND", "_VEGETATION_HEIGHT"})
      if (findExtra(part, candidate)) {
        names.push_back(candidate);
        break;
      }
    if (findExtra(part, "_CLASS")) names.push_back("_CLASS");
    if (names.empty())
      throw InputError(where + " has no terrain attribute (_HEIGHT_ABOVE_GROUND, _VEGETATION_HEIGHT or _CLASS); "
                       "make one with `geoshift terrain`, or name the attribute with --signal");
  }
  if (names.empty()) throw InputError("--signal names no attribute");
  for (const std::string& name : names) {
    double hr = 0;
    RangeKernel kernel = RangeKernel::Gaussian;
    if (name == "color") {
      if (part.colors.empty())
        throw InputError(where + " has no vertex colors (COLOR_0); choose --signal normal, curvature or an attribute");
      std::vector<double> rgb;
      for (const Eigen::Vector4d& c : part.colors) rgb.insert(rgb.end(), {c[0], c[1], c[2]});
      set.set("COLOR", 3, AttributeKind::Euclidean, toMeshLayout(rgb, 3, build.vertexOf, mesh));
      sources.push_back({"color", "COLOR"});
      hr = 0.1;
    } else if (name == "normal") {
      std::vector<double> flat;
      for (const Vec3& v : vertexNormals(mesh)) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
      set.set("NORMAL", 3, AttributeKind::UnitVector, flat);
      sources.push_back({"normal", "NORMAL"});
      kernel = RangeKernel::NormalSimilarity;
      hr = 0.45;
    } else if (name == "curvature") {
      std::vector<double> k = curvatures(mesh).get(CurvatureKind::Absolute);
      hr = spreadBandwidth(k, 1);
      set.set("_CURVATURE", 1, AttributeKind::Euclidean, std::move(k));
      sources.push_back({"curvature", "_CURVATURE"});
    } else {
      const ExtraAttribute* e = findExtra(part, name);
      if (!e) {
        std::string known;
        for (const ExtraAttribute& x : part.extras) known += (known.empty() ? "" : ", ") + x.name;
        throw InputError(where + " has no attribute '" + name + "' (it has: " + (known.empty() ? "none" : known) +
                         "; or use color, normal, curvature)");
      }
      std::vector<double> values = toMeshLayout(e->values, e->dim, build.vertexOf, mesh);
      hr = spreadBandwidth(values, e->dim);
      set.set(e->name, e->dim, AttributeKind::Euclidean, std::move(values));
      sources.push_back({"extra", e->name});
    }
    options.channels.push_back({sources.back().name, settings.rangeGiven ? settings.options.rangeBandwidth : hr, kernel});
  }

  Progress progress;
  if (isatty(STDERR_FILENO))
    progress.report = [](double f, std::string_view stage) {
      std::cerr << "\r" << stage << " " << static_cast<int>(100 * f) << "%   " << std::flush;
    };
  HybridResult hybrid = hybridMeanShift(mesh, set, options, settings.hybrid, progress);
  if (progress.report) std::cerr << "\n";
  if (settings.hybrid.levels > 0) {
    std::cerr << "geoshift: " << part.label << ": vertices per level";
    for (int count : hybrid.vertexCounts) std::cerr << " " << count;
    std::cerr << " (filtered the last)\n";
  }
  if (settings.hybrid.filterGeometry) {
    for (size_t i = 0; i < part.positions.size(); ++i) part.positions[i] = hybrid.positions[build.vertexOf[i]];
  }
  const AttributeSet& filtered = hybrid.signal;

  for (const Source& s : sources) {
    const Attribute& out = filtered.get(s.name);
    const std::vector<double> values = toCallerLayout(out.values, out.dim, build.vertexOf);
    if (s.kind == "color") {
      for (size_t i = 0; i < part.colors.size(); ++i)
        part.colors[i].head<3>() = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    } else if (s.kind == "normal") {
      part.normals.resize(part.positions.size());
      for (size_t i = 0; i < part.normals.size(); ++i) part.normals[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    } else {
      if (s.kind == "curvature") {
        const std::vector<double> rgb = colorMap(values);
        part.colors.resize(values.size());
        for (size_t i = 0; i < values.size(); ++i) part.colors[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 1.0};
      }
      std::erase_if(part.extras, [&](const ExtraAttribute& e) { return e.name == s.name; });
      part.extras.push_back({s.name, out.dim, values});
    }
  }
  if (options.segments) {
    std::vector<double> labels(hybrid.segment.begin(), hybrid.segment.end());
    std::erase_if(part.extras, [](const ExtraAttribute& e) { return e.name == "_SEGMENT"; });
    part.extras.push_back({"_SEGMENT", 1, toCallerLayout(labels, 1, build.vertexOf)});
    std::cerr << "geoshift: " << part.label << ": " << hybrid.segmentCount << " segments\n";
  }
  return hybrid;
}

}  // namespace geoshift::cli

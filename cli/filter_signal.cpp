#include "filter_signal.hpp"

#include <algorithm>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift::cli {

namespace {

// The part's colors and extra attributes, as the core's filter request reads them.
SignalInputs inputsOf(const Document& doc, const MeshPart& part, const MeshBuild* build) {
  SignalInputs in;
  in.where = doc.path + ": " + part.label;
  for (const ExtraAttribute& e : part.extras) in.attributeNames.push_back(e.name);
  if (!build) {  // names only (missingSignal)
    if (!part.colors.empty()) in.colors = [] { return std::vector<double>(); };
    return in;
  }
  if (!part.colors.empty())
    in.colors = [&part, build] {
      std::vector<double> rgb;
      rgb.reserve(3 * part.colors.size());
      for (const Eigen::Vector4d& c : part.colors) rgb.insert(rgb.end(), {c[0], c[1], c[2]});
      return toMeshLayout(rgb, 3, build->vertexOf, build->mesh);
    };
  in.attribute = [&part, build](const std::string& name) {
    const auto e = std::find_if(part.extras.begin(), part.extras.end(), [&](const ExtraAttribute& x) { return x.name == name; });
    return Attribute{e->name, e->dim, AttributeKind::Euclidean, toMeshLayout(e->values, e->dim, build->vertexOf, build->mesh)};
  };
  return in;
}

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
  return geoshift::missingSignal(settings.signal, inputsOf(doc, part, nullptr));
}

HybridResult filterPart(const Document& doc, MeshPart& part, const MeshBuild& build, const FilterSettings& settings) {
  const Mesh& mesh = build.mesh;
  Progress progress;
  if (isatty(STDERR_FILENO))
    progress.report = [](double f, std::string_view stage) {
      std::cerr << "\r" << stage << " " << static_cast<int>(100 * f) << "%   " << std::flush;
    };
  const FilterSignal signal = filterSignal(mesh, settings.signal, inputsOf(doc, part, &build),
                                           settings.rangeGiven ? std::optional(settings.options.rangeBandwidth) : std::nullopt,
                                           progress);
  MeanShiftOptions options = settings.options;
  options.channels = signal.channels;
  HybridResult hybrid = hybridMeanShift(mesh, signal.values, options, settings.hybrid, progress);
  if (progress.report) std::cerr << "\n";
  if (settings.hybrid.levels > 0) {
    std::cerr << "geoshift: " << part.label << ": vertices per level";
    for (int count : hybrid.vertexCounts) std::cerr << " " << count;
    std::cerr << " (filtered the last)\n";
  }
  if (settings.hybrid.filterGeometry) {
    for (size_t i = 0; i < part.positions.size(); ++i) part.positions[i] = hybrid.positions[build.vertexOf[i]];
    recomputeNormals(part);  // a filtered "normal" signal, below, replaces them
  }
  const AttributeSet& filtered = hybrid.signal;

  for (size_t c = 0; c < signal.channels.size(); ++c) {
    const std::string& name = signal.channels[c].attribute;
    const Attribute& out = filtered.get(name);
    const std::vector<double> values = toCallerLayout(out.values, out.dim, build.vertexOf);
    switch (signal.sources[c]) {
      case SignalSource::Color:
        for (size_t i = 0; i < part.colors.size(); ++i)
          part.colors[i].head<3>() = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
        break;
      case SignalSource::Normal:
        part.normals.resize(part.positions.size());
        for (size_t i = 0; i < part.normals.size(); ++i)
          part.normals[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
        break;
      case SignalSource::Curvature: {
        const std::vector<double> rgb = colorMap(values);
        part.colors.resize(values.size());
        for (size_t i = 0; i < values.size(); ++i) part.colors[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 1.0};
      }
        [[fallthrough]];
      case SignalSource::Attribute:
        std::erase_if(part.extras, [&](const ExtraAttribute& e) { return e.name == name; });
        part.extras.push_back({name, out.dim, values});
        break;
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

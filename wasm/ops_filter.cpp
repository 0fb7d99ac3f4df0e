// op "filter": Riemannian mean shift (mode "ms") or blurring mean shift ("bms") of a vertex signal,
// directly or on a wavelet-coarsened mesh (levels > 0, Algorithm 2). What the request means is the
// core's (filter_request.hpp), as for `geoshift filter`, so both give the same numbers.
#include <optional>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/hybrid.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

namespace {

// The session's colors and one-number signals, as the core's filter request reads them.
SignalInputs inputsOf(const Session& s) {
  SignalInputs in;
  in.where = "filter: the mesh";
  if (const Attribute* color = s.attributes.find("color")) in.colors = [color] { return color->values; };
  for (const Attribute& a : s.attributes.all())
    if (a.name != "color" && a.name != "normal") in.attributeNames.push_back(a.name);
  in.attribute = [&s](const std::string& name) {
    const Attribute& a = s.attributes.get(name);
    if (a.dim != 1)
      throw InputError("filter: attribute '" + a.name + "' has " + std::to_string(a.dim) +
                       " numbers per vertex; this op filters one-number attributes (and color, normal)");
    return Attribute{a.name, 1, AttributeKind::Euclidean, a.values};
  };
  return in;
}

}  // namespace

OpOutput runFilter(const OpContext& context) {
  const ParamRequest& p = context.params;
  const Session& s = context.session;
  const Mesh& mesh = s.build.mesh;

  // levels > 0: the hybrid filter (Algorithm 2), the mean shift on a wavelet-coarsened mesh with
  // the details added back times alpha; 0 is the plain mean shift, as in the CLI.
  const FilterRequest request = filterRequest(p);
  MeanShiftOptions o = request.options;
  o.parallel.threads = context.threads(o.parallel.threads);
  const HybridOptions& hybrid = request.hybrid;

  const FilterSignal signal = filterSignal(mesh, request.signal, inputsOf(s), request.rangeBandwidth, context.progress);
  o.channels = signal.channels;
  HybridResult r = hybridMeanShift(mesh, signal.values, o, hybrid, context.progress);

  OpOutput out;
  if (hybrid.filterGeometry) out.positions = std::move(r.positions);
  for (size_t c = 0; c < signal.channels.size(); ++c) {
    const std::string& name = signal.channels[c].attribute;
    std::vector<double> values = r.signal.get(name).values;
    switch (signal.sources[c]) {
      case SignalSource::Color:
        out.colors = std::move(values);
        out.colorsAreSignal = true;
        break;
      case SignalSource::Normal:
        out.normals = std::move(values);
        break;
      case SignalSource::Curvature: {
        // The CLI maps colors over the caller's vertices (its percentiles count every welded copy).
        const std::vector<int>& vertexOf = s.build.vertexOf;
        const std::vector<double> rgb = colorMap(toCallerLayout(values, 1, vertexOf));
        std::vector<double> meshRgb(3 * values.size(), 0.0);
        for (std::size_t i = 0; i < vertexOf.size(); ++i)
          for (int k = 0; k < 3; ++k) meshRgb[3 * vertexOf[i] + k] = rgb[3 * i + k];
        if (!out.colorsAreSignal) out.colors = std::move(meshRgb);
        out.scalars.emplace_back(name, std::move(values));
        break;
      }
      case SignalSource::Attribute:
        out.scalars.emplace_back(name, std::move(values));
        break;
    }
  }
  if (o.segments) {
    out.scalars.emplace_back("_SEGMENT", std::vector<double>(r.segment.begin(), r.segment.end()));
    out.stats.set("segmentCount", r.segmentCount);
  }
  out.stats.set("signal", request.signal);
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

// The filters of a named signal: mean shift and the hybrid filter (the request rules of `geoshift
// filter`, the core's filter_request.hpp, so both give the same numbers), the presets, what tiles
// need to share one unit, and curvature. bindFilters also registers denoise.cpp and wavelets.cpp.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <tuple>

#include "bindings.hpp"
#include "geoshift/curvature.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/hybrid.hpp"
#include "geoshift/presets.hpp"
#include "options.hpp"

namespace geoshift::python {

namespace {

struct Source {
  std::string kind;  // color, normal, curvature, attribute
  std::string name;  // in the filtered set
};

py::dict meanShiftCall(Built& b, const std::vector<std::string>& signal, const py::handle& colors, const py::dict& attributes,
                       const std::vector<std::string>& unitVectors, const MeanShiftOptions& given, bool rangeGiven,
                       int levels, const std::vector<double>& alpha, bool filterGeometry, const WaveletOptions& wavelet,
                       double unit, const py::object& callback) {
  const Inputs in = inputsOf(b, colors, attributes, unitVectors);
  const Mesh& mesh = b.mesh();
  MeanShiftOptions options = given;
  const bool channelsGiven = !given.channels.empty();
  HybridOptions hybrid;
  hybrid.levels = levels;
  hybrid.alpha = alpha;
  hybrid.filterGeometry = filterGeometry;
  hybrid.wavelet = onMesh(b, wavelet);
  hybrid.unit = unit;

  Run run(callback);
  std::vector<Source> sources;
  const HybridResult r = run([&](const Progress& progress) {
    // What the names mean is the core's (filter_request.hpp), as for `geoshift filter --signal`.
    SignalInputs inputs;
    if (!in.colors.empty()) inputs.colors = [&] { return b.toMesh(in.colors, 3); };
    for (const Named& a : in.attributes) inputs.attributeNames.push_back(a.name);
    inputs.attribute = [&](const std::string& name) {
      const Named& a = *std::find_if(in.attributes.begin(), in.attributes.end(), [&](const Named& x) { return x.name == name; });
      return Attribute{a.name, a.dim, a.unit ? AttributeKind::UnitVector : AttributeKind::Euclidean,
                       b.toMesh(a.values, a.dim, a.unit)};
    };
    std::string list;
    for (const std::string& name : signal) list += (list.empty() ? "" : ",") + name;
    const FilterSignal request = filterSignal(mesh, list, inputs, rangeGiven ? std::optional(given.rangeBandwidth) : std::nullopt, progress);
    const AttributeSet& set = request.values;
    const std::vector<SignalChannel>& channels = request.channels;
    static const char* const kinds[] = {"color", "normal", "curvature", "attribute"};
    for (size_t c = 0; c < channels.size(); ++c)
      sources.push_back({kinds[static_cast<int>(request.sources[c])], channels[c].attribute});
    // Channels given by the caller (names of the set above) replace the ones the names imply.
    options.channels = channelsGiven ? given.channels : channels;

    return hybridMeanShift(mesh, set, options, hybrid, progress);
  });

  py::dict out;
  py::list filtered;
  for (const Source& s : sources) {
    const Attribute& a = r.signal.get(s.name);
    filtered.append(py::make_tuple(s.kind, s.name, fromRows(b.toCaller(a.values, a.dim), a.dim)));
  }
  out["signals"] = filtered;
  py::list used;
  for (const SignalChannel& c : options.channels)
    used.append(py::make_tuple(c.attribute, c.rangeBandwidth > 0 ? c.rangeBandwidth : options.rangeBandwidth));
  out["channels"] = used;
  if (filterGeometry) {
    std::vector<Vec3> p(b.callerVertices());
    for (size_t i = 0; i < p.size(); ++i) p[i] = r.positions[b.build.vertexOf[i]];
    out["positions"] = fromPoints(p);
  }
  if (options.segments) {
    std::vector<double> labels(r.segment.begin(), r.segment.end());
    const std::vector<double> caller = b.toCaller(labels, 1);
    out["segment"] = fromVector(std::vector<int>(caller.begin(), caller.end()));
    out["segment_count"] = r.segmentCount;
  }
  const MeanShiftResult& c = r.coarse;
  std::vector<int> converged(c.converged.begin(), c.converged.end());
  if (levels == 0) {
    std::vector<double> it(c.iterations.begin(), c.iterations.end()), conv(converged.begin(), converged.end());
    it = b.toCaller(it, 1);
    conv = b.toCaller(conv, 1);
    out["iterations"] = fromVector(std::vector<int>(it.begin(), it.end()));
    out["converged"] = fromVector(std::vector<int>(conv.begin(), conv.end()));
  } else {
    out["iterations"] = fromVector(c.iterations);
    out["converged"] = fromVector(converged);
  }
  out["vertex_counts"] = r.vertexCounts;
  out["mean_iterations"] = c.meanIterations;
  out["max_iterations"] = c.maxIterations;
  out["converged_fraction"] = c.convergedFraction;
  out["threads"] = c.threads;
  out["seconds"] = r.seconds > 0 ? r.seconds : c.seconds;
  out["start_charts"] = c.diagnostics.startCharts;
  out["charts_computed"] = c.diagnostics.chartsComputed;
  return out;
}

void bindMeanShift(py::module_& m) {
  m.def("_mean_shift", &meanShiftCall, py::arg("built"), py::arg("signal"), py::arg("colors"), py::arg("attributes"),
        py::arg("unit_vectors"), py::arg("options"), py::arg("range_given"), py::arg("levels"), py::arg("alpha"),
        py::arg("filter_geometry"), py::arg("wavelet"), py::arg("unit"), py::arg("progress"));

  m.def("_presets", [] {
    py::list out;
    for (const FilterPreset& p : filterPresets()) {
      py::dict d;
      d["name"] = p.name;
      d["description"] = p.description;
      d["signal"] = p.signal;
      d["options"] = py::cast(p.options);
      d["levels"] = p.levels;
      d["alpha"] = p.detailGain;
      out.append(d);
    }
    return out;
  });
  m.def("_preset", [](const std::string& name) { return filterPreset(name).name; });
  m.def("spread_bandwidth", [](const py::handle& values) {
    int dim = 1;
    return spreadBandwidth(toRows(values, "values", dim), dim);
  }, py::arg("values"), "The default h_r of a signal: a tenth of its widest 10-90% spread over its columns (1 when 0).");
}

// What geoshift.tiles needs so that tiles filter as the whole would.
void bindTileSupport(py::module_& m) {
  // Sum and count of the coarse mesh's edge lengths after `levels` wavelet levels, over the edges
  // whose ends are `owned` (caller vertices; an edge with one owned end counts half): summed over
  // tiles, the whole surface's coarse AEL, the unit of a tiled hybrid filter's spatial options.
  // Third, each level's cost-band bounds (WaveletLevel::costBounds): with the whole's, a tile's
  // analysis orders its candidates as the whole's does (WaveletOptions::costBounds).
  m.def("_coarse_edge_stats", [](Built& b, int levels, const WaveletOptions& wavelet, const py::handle& ownedArray,
                                 const py::object& callback) {
    int dim = 1;
    const std::vector<double> ownedCaller = toRows(ownedArray, "owned", dim);
    if (dim != 1 || ownedCaller.size() != static_cast<size_t>(b.callerVertices()))
      throw InputError("owned must have one value per vertex");
    const std::vector<double> owned = b.toMesh(ownedCaller, 1);
    Run run(callback);
    return run([&](const Progress& progress) {
      const Mesh* coarse = &b.mesh();
      std::vector<int> toFine;
      Multiresolution mr;
      if (levels > 0) {
        WaveletOptions w = onMesh(b, wavelet);
        w.levels = levels;
        mr = analyze(b.mesh(), AttributeSet(b.mesh().vertexCount()), w, progress);
        coarse = &mr.coarse;
        toFine = mr.coarseToFine;
      }
      double sum = 0, count = 0;
      std::vector<std::vector<double>> bounds;
      for (const WaveletLevel& l : mr.levels) bounds.push_back(l.costBounds);
      for (int h = 0; h < coarse->halfedgeCount(); ++h) {
        const int t = coarse->twin(h);
        if (t >= 0 && t < h) continue;
        int u = coarse->tail(h), v = coarse->head(h);
        if (levels > 0) u = toFine[u], v = toFine[v];
        const double weight = 0.5 * ((owned[u] > 0.5) + (owned[v] > 0.5));
        if (weight == 0) continue;
        sum += weight * (coarse->position(coarse->head(h)) - coarse->position(coarse->tail(h))).norm();
        count += weight;
      }
      return std::make_tuple(sum, count, bounds);
    });
  });
}

void bindCurvatures(py::module_& m) {
  m.def("_curvatures", [](Built& b) {
    Run run;
    const Curvatures k = run([&](const Progress&) { return curvatures(b.mesh()); });
    py::dict out;
    for (auto [name, kind] : {std::pair{"mean", CurvatureKind::Mean}, std::pair{"gaussian", CurvatureKind::Gaussian},
                              std::pair{"absolute", CurvatureKind::Absolute}, std::pair{"rms", CurvatureKind::Rms}})
      out[name] = fromVector(b.toCaller(k.get(kind), 1));
    out["area"] = fromVector(b.toCaller(k.area, 1));
    return out;
  });

  m.def("color_map", [](const py::handle& values) {
    int dim = 1;
    const std::vector<double> v = toRows(values, "values", dim);
    if (dim != 1) throw InputError("color_map takes one value per vertex");
    return fromRows(colorMap(v), 3);
  }, py::arg("values"),
        "RGB in [0, 1] for a scalar field: blue-white-red when it has both signs, else sequential; clamped at the 10% "
        "and 90% percentiles (as `geoshift curvature` colors).");
}

}  // namespace

void bindFilters(py::module_& m) {
  bindMeanShift(m);
  bindTileSupport(m);
  bindCurvatures(m);
  bindDenoising(m);
  bindWavelets(m);
}

}  // namespace geoshift::python

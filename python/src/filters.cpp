// The filters: mean shift and the hybrid filter of a named signal (the request rules of
// `geoshift filter`, cli/filter_signal.cpp, so both give the same numbers), denoising, smoothing,
// wavelet analysis and synthesis, curvature.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <tuple>

#include "bindings.hpp"
#include "geoshift/bilateral_normal.hpp"
#include "geoshift/curvature.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/hybrid.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/smoothing.hpp"
#include "options.hpp"

namespace geoshift::python {

namespace {

// The caller's per-vertex data that a signal name may refer to, copied out of Python.
struct Named {
  std::string name;
  int dim = 1;
  bool unit = false;
  std::vector<double> values;  // caller layout
};

struct Inputs {
  std::vector<double> colors;  // caller layout RGB, empty when none
  std::vector<Named> attributes;
};

Inputs inputsOf(const Built& b, const py::handle& colors, const py::dict& attributes, const std::vector<std::string>& unit) {
  Inputs in;
  const size_t n = b.callerVertices();
  if (!colors.is_none()) {
    int dim = 0;
    std::vector<double> rows = toRows(colors, "colors", dim);
    if ((dim != 3 && dim != 4) || rows.size() != n * dim)
      throw InputError("colors must have shape (N, 3) or (N, 4) for the mesh's " + std::to_string(n) + " vertices");
    for (size_t i = 0; i < n; ++i) in.colors.insert(in.colors.end(), {rows[dim * i], rows[dim * i + 1], rows[dim * i + 2]});
  }
  for (auto [k, v] : attributes) {
    Named a;
    a.name = py::str(k);
    a.values = toRows(v, "attribute '" + a.name + "'", a.dim);
    if (a.values.size() != n * a.dim)
      throw InputError("attribute '" + a.name + "' has " + std::to_string(a.values.size() / a.dim) + " rows for the mesh's " +
                       std::to_string(n) + " vertices");
    a.unit = std::find(unit.begin(), unit.end(), a.name) != unit.end();
    in.attributes.push_back(std::move(a));
  }
  return in;
}

// The wavelet options of a call with WaveletOptions::wholeIndex, which Python gives per caller
// vertex, per mesh vertex (welded vertices take their smallest).
WaveletOptions onMesh(const Built& b, WaveletOptions w) {
  if (w.wholeIndex.empty()) return w;
  const size_t n = b.callerVertices();
  if (w.wholeIndex.size() != n)
    throw InputError("wavelet whole_index has " + std::to_string(w.wholeIndex.size()) + " entries for the mesh's " +
                     std::to_string(n) + " vertices");
  std::vector<std::int64_t> index(b.mesh().vertexCount(), std::numeric_limits<std::int64_t>::max());
  for (size_t i = 0; i < n; ++i) index[b.build.vertexOf[i]] = std::min(index[b.build.vertexOf[i]], w.wholeIndex[i]);
  w.wholeIndex = std::move(index);
  return w;
}

struct Source {
  std::string kind;  // color, normal, curvature, attribute
  std::string name;  // in the filtered set
};

// Spatial options are multiples of the filtered mesh's AEL; times `factor` makes them multiples of
// another length.
void scaleSpatial(MeanShiftOptions& o, double factor) {
  o.spatialBandwidth *= factor;
  o.radius *= factor;  // 0 stays 0: 3 h_s, scaled with h_s
  o.epsilon *= factor;
}

// hybridMeanShift with the spatial options in multiples of `unit` (an absolute length) instead of
// the filtered mesh's AEL, so that pieces of one surface (tiles) filter with the same bandwidths.
// The same steps as core/src/hybrid.cpp.
HybridResult hybridInUnits(const Mesh& mesh, const AttributeSet& signal, MeanShiftOptions options,
                           const HybridOptions& hybrid, double unit, const Progress& progress) {
  if (hybrid.levels <= 0) {
    scaleSpatial(options, unit / averageEdgeLength(mesh));
    return hybridMeanShift(mesh, signal, options, hybrid, progress);
  }
  HybridResult result;
  AttributeSet channels(mesh.vertexCount());
  for (const SignalChannel& c : options.channels) {
    const Attribute& a = signal.get(c.attribute);
    channels.set(a.name, a.dim, a.kind, a.values);
  }
  WaveletOptions w = hybrid.wavelet;
  w.levels = hybrid.levels;
  const Multiresolution mr = analyze(mesh, channels, w, progress.slice(0, 0.1));
  result.vertexCounts = mr.vertexCounts();
  scaleSpatial(options, unit / averageEdgeLength(mr.coarse));
  result.coarse = meanShift(mr.coarse, mr.coarseAttributes, options, progress.slice(0.1, 0.95));
  const SynthesisResult fine = synthesize(mr, mr.coarse.positions(), result.coarse.signal, hybrid.alpha, progress.slice(0.95, 1));
  result.signal = fine.attributes;
  result.positions = hybrid.filterGeometry ? fine.mesh.positions() : mesh.positions();
  if (options.segments) {
    result.segment.assign(mesh.vertexCount(), -1);
    for (size_t c = 0; c < mr.coarseToFine.size(); ++c) result.segment[mr.coarseToFine[c]] = result.coarse.segment[c];
    for (auto level = mr.levels.rbegin(); level != mr.levels.rend(); ++level)
      for (size_t i = level->odd.size(); i-- > 0;) result.segment[level->odd[i]] = result.segment[level->target[i]];
    result.segmentCount = result.coarse.segmentCount;
  }
  return result;
}

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

    return unit > 0 ? hybridInUnits(mesh, set, options, hybrid, unit, progress)
                    : hybridMeanShift(mesh, set, options, hybrid, progress);
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

}  // namespace

void bindFilters(py::module_& m) {
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

  m.def("_denoise", [](Built& b, const DenoiseOptions& options, const py::object& callback) {
    Run run(callback);
    Mesh mesh = b.mesh();
    const DenoiseResult r = run([&](const Progress& p) { return denoise(mesh, options, p); });
    py::dict out;
    std::vector<Vec3> positions(b.callerVertices());
    for (size_t i = 0; i < positions.size(); ++i) positions[i] = mesh.position(b.build.vertexOf[i]);
    out["positions"] = fromPoints(positions);
    out["noise_level"] = r.noiseLevel;
    out["noise_estimated"] = r.noiseEstimated;
    out["presmoothing_steps"] = r.presmoothingSteps;
    out["passes"] = r.passes;
    out["passes_run"] = r.passesRun;
    out["estimated_error"] = r.estimatedError;
    out["mean_iterations"] = r.meanIterations;
    out["converged_fraction"] = r.convergedFraction;
    out["limited_steps"] = r.limitedSteps;
    out["threads"] = r.threads;
    out["filtered_vertices"] = r.filteredVertices;
    out["seconds"] = r.seconds;
    return out;
  });

  m.def("_bilateral", [](Built& b, const BilateralNormalOptions& options, const py::object& callback) {
    Run run(callback);
    Mesh mesh = b.mesh();
    const BilateralNormalResult r = run([&](const Progress& p) { return bilateralNormalDenoise(mesh, options, p); });
    std::vector<Vec3> positions(b.callerVertices());
    for (size_t i = 0; i < positions.size(); ++i) positions[i] = mesh.position(b.build.vertexOf[i]);
    py::dict out;
    out["positions"] = fromPoints(positions);
    out["sigma_spatial"] = r.sigmaSpatial;
    out["limited_steps"] = r.vertexUpdate.limitedSteps;
    return out;
  });

  m.def("_taubin", [](Built& b, const TaubinOptions& options, const py::object& callback) {
    Run run(callback);
    Mesh mesh = b.mesh();
    run([&](const Progress& p) {
      taubinSmooth(mesh, options, p);
      return 0;
    });
    std::vector<Vec3> positions(b.callerVertices());
    for (size_t i = 0; i < positions.size(); ++i) positions[i] = mesh.position(b.build.vertexOf[i]);
    return fromPoints(positions);
  });

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

  // Wavelets: a Multiresolution of the welded mesh, kept with it.
  struct Analysis {
    std::shared_ptr<Built> built;
    Multiresolution mr;
  };
  py::class_<Analysis, std::shared_ptr<Analysis>>(m, "_Multiresolution")
      .def_property_readonly("vertex_counts", [](const Analysis& a) { return a.mr.vertexCounts(); })
      .def_property_readonly("level_count", [](const Analysis& a) { return a.mr.levelCount(); })
      .def_property_readonly("coarse_positions", [](const Analysis& a) { return fromPoints(a.mr.coarse.positions()); })
      .def_property_readonly("coarse_faces", [](const Analysis& a) { return fromFaces(a.mr.coarse.faces()); })
      .def_property_readonly("coarse_to_mesh", [](const Analysis& a) { return fromVector(a.mr.coarseToFine); })
      .def_property_readonly("cost_bounds", [](const Analysis& a) {
        std::vector<std::vector<double>> bounds;
        for (const WaveletLevel& l : a.mr.levels) bounds.push_back(l.costBounds);
        return bounds;
      })
      .def_property_readonly("coarse_attributes", [](const Analysis& a) {
        py::dict out;
        for (const Attribute& at : a.mr.coarseAttributes.all()) out[at.name.c_str()] = fromRows(at.values, at.dim);
        return out;
      });

  m.def("_analyze", [](std::shared_ptr<Built> b, const py::dict& attributes, const std::vector<std::string>& unit,
                       const WaveletOptions& options, const py::object& callback) {
    const Inputs in = inputsOf(*b, py::none(), attributes, unit);
    AttributeSet set(b->mesh().vertexCount());
    for (const Named& a : in.attributes)
      set.set(a.name, a.dim, a.unit ? AttributeKind::UnitVector : AttributeKind::Euclidean, b->toMesh(a.values, a.dim, a.unit));
    Run run(callback);
    auto a = std::make_shared<Analysis>();
    a->built = b;
    const WaveletOptions w = onMesh(*b, options);
    a->mr = run([&](const Progress& p) { return analyze(b->mesh(), set, w, p); });
    return a;
  });

  m.def("_synthesize", [](const Analysis& a, const py::handle& coarsePositions, const py::handle& coarseAttributes,
                          const std::vector<double>& alpha, const py::object& callback) {
    const Multiresolution& mr = a.mr;
    std::vector<Vec3> positions = coarsePositions.is_none() ? mr.coarse.positions() : toPoints(coarsePositions, "coarse positions");
    AttributeSet attributes = mr.coarseAttributes;
    if (!coarseAttributes.is_none())
      for (auto [k, v] : py::cast<py::dict>(coarseAttributes)) {
        const std::string name = py::str(k);
        const Attribute* old = mr.coarseAttributes.find(name);
        if (!old) throw InputError("the analysis has no attribute '" + name + "'");
        int dim = 1;
        attributes.set(name, old->dim, old->kind, toRows(v, "coarse attribute '" + name + "'", dim));
      }
    Run run(callback);
    const SynthesisResult r = run([&](const Progress& p) { return synthesize(mr, positions, attributes, alpha, p); });
    const Built& b = *a.built;
    std::vector<Vec3> caller(b.callerVertices());
    for (size_t i = 0; i < caller.size(); ++i) caller[i] = r.mesh.position(b.build.vertexOf[i]);
    py::dict out;
    out["positions"] = fromPoints(caller);
    py::dict attrs;
    for (const Attribute& at : r.attributes.all()) attrs[at.name.c_str()] = fromRows(b.toCaller(at.values, at.dim), at.dim);
    out["attributes"] = attrs;
    return out;
  });

  // `geoshift wavelet` on one part (cli/wavelet.cpp): positions and, unless positionsOnly, the
  // colors' change (clamped to [0, 1]) in the caller's layout.
  m.def("_wavelet_filter", [](Built& b, const py::handle& colors, int levels, const std::vector<double>& alpha,
                              bool positionsOnly, const py::object& callback) {
    const Inputs in = inputsOf(b, colors, py::dict(), {});
    const bool withColors = !in.colors.empty() && !positionsOnly;
    AttributeSet signals(b.mesh().vertexCount());
    std::vector<double> before;
    if (withColors) {
      before = b.toMesh(in.colors, 3);
      signals.set("color", 3, AttributeKind::Euclidean, before);
    }
    WaveletOptions o;
    o.levels = levels;
    Run run(callback);
    Multiresolution mr;
    const SynthesisResult r = run([&](const Progress& p) {
      mr = analyze(b.mesh(), signals, o, p.slice(0, 0.8));
      return synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, alpha, p.slice(0.8, 1));
    });
    py::dict out;
    std::vector<Vec3> positions(b.callerVertices());
    for (size_t i = 0; i < positions.size(); ++i) positions[i] = r.mesh.position(b.build.vertexOf[i]);
    out["positions"] = fromPoints(positions);
    if (withColors) {
      const std::vector<double>& after = r.attributes.get("color").values;
      int dim = 0;
      std::vector<double> rows = toRows(colors, "colors", dim);
      for (size_t i = 0; i < positions.size(); ++i) {
        const int v = b.build.vertexOf[i];
        for (int c = 0; c < 3; ++c) rows[dim * i + c] = std::clamp(rows[dim * i + c] + after[3 * v + c] - before[3 * v + c], 0.0, 1.0);
      }
      out["colors"] = fromRows(rows, dim);
    }
    out["vertex_counts"] = mr.vertexCounts();
    return out;
  });
}

}  // namespace geoshift::python

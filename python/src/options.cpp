#include "options.hpp"

#include <algorithm>

#include "geoshift/bilateral_normal.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/hybrid.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/terrain.hpp"

namespace geoshift::python {

namespace {

// The property names of a bound options class (its fields), sorted.
std::vector<std::string> fieldsOf(const py::handle& type) {
  const py::object property = py::module_::import("builtins").attr("property");
  std::vector<std::string> names;
  for (const py::handle& name : py::module_::import("builtins").attr("dir")(type)) {
    const std::string n = py::str(name);
    if (n.empty() || n[0] == '_') continue;
    if (py::isinstance(type.attr(name), property)) names.push_back(n);
  }
  return names;
}

py::dict toDict(const py::handle& self) {
  py::dict out;
  for (const std::string& name : fieldsOf(py::type::handle_of(self))) {
    py::object value = self.attr(name.c_str());
    if (py::hasattr(value, "to_dict")) {
      value = value.attr("to_dict")();
    } else if (py::isinstance<py::list>(value)) {
      py::list items;
      for (const py::handle& item : value) items.append(py::hasattr(item, "to_dict") ? item.attr("to_dict")() : py::reinterpret_borrow<py::object>(item));
      value = items;
    }
    out[name.c_str()] = value;
  }
  return out;
}

// kwargs constructor, repr, equality by fields, to_dict and pickling (Dask ships options to workers).
template <class T>
py::class_<T> optionsClass(py::module_& m, const char* name, const char* doc) {
  py::class_<T> c(m, name, doc);
  c.def(py::init([](const py::kwargs& kw) {
          T t;
          applyOptions(py::cast(&t, py::return_value_policy::reference), kw);
          return t;
        }),
        "Options with the library's defaults; keyword arguments set fields.");
  c.def("to_dict", [](py::handle self) { return toDict(self); }, "The fields as a dict (nested options as dicts).");
  c.def("__repr__", [name](py::handle self) {
    std::string s = std::string(name) + "(";
    bool first = true;
    for (auto [k, v] : toDict(self)) {
      s += (first ? "" : ", ") + std::string(py::str(k)) + "=" + std::string(py::repr(v));
      first = false;
    }
    return s + ")";
  });
  c.def("__eq__", [](py::handle a, py::handle b) {
    return py::type::handle_of(a).is(py::type::handle_of(b)) && toDict(a).equal(toDict(b));
  });
  c.def(py::pickle([](py::handle self) { return toDict(self); },
                   [](const py::dict& d) {
                     T t;
                     applyOptions(py::cast(&t, py::return_value_policy::reference), d);
                     return t;
                   }));
  return c;
}

}  // namespace

void applyOptions(py::handle target, const py::dict& values) {
  const py::handle type = py::type::handle_of(target);
  const std::vector<std::string> fields = fieldsOf(type);
  for (auto [k, v] : values) {
    const std::string key = py::str(k);
    if (std::find(fields.begin(), fields.end(), key) == fields.end()) {
      std::string known;
      for (const std::string& f : fields) known += (known.empty() ? "" : ", ") + f;
      throw py::type_error(std::string(py::str(type.attr("__name__"))) + " has no option '" + key + "' (options: " + known + ")");
    }
    py::object current = target.attr(key.c_str());
    if (py::isinstance<py::dict>(v) && py::hasattr(current, "to_dict"))
      applyOptions(current, py::reinterpret_borrow<py::dict>(v));  // a nested struct, set in place
    else
      target.attr(key.c_str()) = v;
  }
}

void bindOptions(py::module_& m) {
  m.def("_apply_options", [](py::handle target, const py::dict& values) { applyOptions(target, values); });
  auto parallel = optionsClass<ParallelOptions>(m, "ParallelOptions", "Threads of the per-vertex filters.");
  parallel.def_readwrite("threads", &ParallelOptions::threads, "0: all hardware threads; results do not depend on it")
      .def_readwrite("chunk", &ParallelOptions::chunk)
      .def_readwrite("report_seconds", &ParallelOptions::reportSeconds);

  auto channel = optionsClass<SignalChannel>(m, "SignalChannel", "One attribute of the signal and how it is compared.");
  channel.def(py::init([](const py::dict& d) { return optionsFrom<SignalChannel>(d); }))
      .def(py::init([](const py::tuple& t) {
        if (t.size() < 1 || t.size() > 3) throw InputError("a channel tuple is (attribute, range_bandwidth=0, kernel='gaussian')");
        SignalChannel c;
        py::object o = py::cast(&c, py::return_value_policy::reference);
        o.attr("attribute") = t[0];
        if (t.size() > 1) o.attr("range_bandwidth") = t[1];
        if (t.size() > 2) o.attr("kernel") = t[2];
        return c;
      }))
      .def_readwrite("attribute", &SignalChannel::attribute)
      .def_readwrite("range_bandwidth", &SignalChannel::rangeBandwidth, "h_r; 0: MeanShiftOptions.range_bandwidth");
  const std::vector<std::pair<std::string, RangeKernel>> kernels = {{"gaussian", RangeKernel::Gaussian},
                                                                    {"normal_similarity", RangeKernel::NormalSimilarity}};
  enumField(channel, "kernel", &SignalChannel::kernel, kernels);
  py::implicitly_convertible<py::dict, SignalChannel>();
  py::implicitly_convertible<py::tuple, SignalChannel>();

  // The speed and accuracy knobs (MeanShiftTuning) stay flat keywords in Python.
#define TUNING(field)                                                             \
  [](const MeanShiftOptions& o) { return o.tuning.field; },                       \
      [](MeanShiftOptions& o, decltype(MeanShiftTuning::field) v) { o.tuning.field = v; }
  auto ms = optionsClass<MeanShiftOptions>(m, "MeanShiftOptions",
                                           "Options of the Riemannian (blurring) mean shift; spatial ones in average "
                                           "edge lengths (AEL), range ones in the signal's units.");
  ms.def_readwrite("channels", &MeanShiftOptions::channels)
      .def_readwrite("range_bandwidth", &MeanShiftOptions::rangeBandwidth)
      .def_readwrite("spatial_bandwidth", &MeanShiftOptions::spatialBandwidth)
      .def_readwrite("radius", &MeanShiftOptions::radius)
      .def_readwrite("epsilon", &MeanShiftOptions::epsilon)
      .def_readwrite("max_iterations", &MeanShiftOptions::maxIterations)
      .def_readwrite("passes", &MeanShiftOptions::passes)
      .def_property("exact_charts", TUNING(exactCharts))
      .def_property("recentre", TUNING(recentre))
      .def_property("chart_cell", TUNING(chartCell))
      .def_property("chart_distortion", TUNING(chartDistortion))
      .def_property("chart_cache_bytes", TUNING(chartCacheBytes))
      .def_readwrite("area_weighted", &MeanShiftOptions::areaWeighted)
      .def_property("single_precision_kernel", TUNING(singlePrecisionKernel))
      .def_readwrite("segments", &MeanShiftOptions::segments)
      .def_readwrite("parallel", &MeanShiftOptions::parallel)
      .def_property(
          "threads", [](const MeanShiftOptions& o) { return o.parallel.threads; },
          [](MeanShiftOptions& o, int t) { o.parallel.threads = t; }, "parallel.threads");
#undef TUNING
  enumField(ms, "range_kernel", &MeanShiftOptions::rangeKernel, kernels);
  enumField(ms, "range_update", &MeanShiftOptions::rangeUpdate,
            {{"sampled", RangeUpdate::Sampled}, {"joint", RangeUpdate::Joint}});

  auto wavelet = optionsClass<WaveletOptions>(m, "WaveletOptions", "Lifting wavelet analysis.");
  wavelet.def_readwrite("levels", &WaveletOptions::levels)
      .def_readwrite("boundary_angle", &WaveletOptions::boundaryAngle)
      .def_readwrite("max_normal_change", &WaveletOptions::maxNormalChange)
      .def_readwrite("keep_level_meshes", &WaveletOptions::keepLevelMeshes)
      .def_readwrite("whole_index", &WaveletOptions::wholeIndex,
                     "For a piece (tile) of a larger mesh: each vertex's index in the whole, increasing "
                     "(docs/tiles.md); empty: its own")
      .def_readwrite("cost_bounds", &WaveletOptions::costBounds,
                     "For a piece (tile) of a larger mesh: the whole's cost-band bounds per level "
                     "(Multiresolution.cost_bounds); empty: this mesh's own");
  enumField(wavelet, "cost", &WaveletOptions::cost, {{"integral", WaveletCost::Integral}, {"residual", WaveletCost::Residual}});
  enumField(wavelet, "weights", &WaveletOptions::weights,
            {{"mean_value", WaveletWeights::MeanValue},
             {"inverse_distance", WaveletWeights::InverseDistance},
             {"uniform", WaveletWeights::Uniform}});

  auto taubin = optionsClass<TaubinOptions>(m, "TaubinOptions", "Taubin lambda|mu smoothing.");
  taubin.def_readwrite("iterations", &TaubinOptions::iterations)
      .def_readwrite("lambda_", &TaubinOptions::lambda)
      .def_readwrite("mu", &TaubinOptions::mu)
      .def_readwrite("parallel", &TaubinOptions::parallel)
      .def_property(
          "threads", [](const TaubinOptions& o) { return o.parallel.threads; },
          [](TaubinOptions& o, int t) { o.parallel.threads = t; }, "parallel.threads");
  enumField(taubin, "weights", &TaubinOptions::weights,
            {{"uniform", LaplacianWeights::Uniform}, {"fujiwara", LaplacianWeights::Fujiwara}, {"cotangent", LaplacianWeights::Cotangent}});

  auto update = optionsClass<VertexUpdateOptions>(m, "VertexUpdateOptions", "Vertex positions from target face normals.");
  update.def_readwrite("iterations", &VertexUpdateOptions::iterations)
      .def_readwrite("area_weighted", &VertexUpdateOptions::areaWeighted)
      .def_readwrite("fixed_boundary", &VertexUpdateOptions::fixedBoundary);
  enumField(update, "flip_guard", &VertexUpdateOptions::flipGuard,
            {{"input", FlipGuard::Input}, {"input_or_target", FlipGuard::InputOrTarget}});

  auto hood = optionsClass<FaceNeighborhoodOptions>(m, "FaceNeighborhoodOptions",
                                                    "Geodesic face neighbourhoods of the default denoiser (AEL units).");
  hood.def_readwrite("radius", &FaceNeighborhoodOptions::radius)
      .def_readwrite("spatial_bandwidth", &FaceNeighborhoodOptions::spatialBandwidth)
      .def_readwrite("parallel", &FaceNeighborhoodOptions::parallel);

  auto paper = optionsClass<PaperDenoiseOptions>(m, "PaperDenoiseOptions", "The paper's 4.1 denoising pipeline.");
  paper.def_readwrite("passes", &PaperDenoiseOptions::passes)
      .def_readwrite("consensus_bandwidth", &PaperDenoiseOptions::consensusBandwidth)
      .def_readwrite("mean_shift", &PaperDenoiseOptions::meanShift)
      .def_readwrite("support", &PaperDenoiseOptions::support)
      .def_readwrite("vertex_update", &PaperDenoiseOptions::vertexUpdate);
  enumField(paper, "face_normals", &PaperDenoiseOptions::faceNormals,
            {{"consensus", FaceNormalRule::Consensus}, {"mean", FaceNormalRule::Mean}});

  auto denoise = optionsClass<DenoiseOptions>(
      m, "DenoiseOptions", "Mesh denoising: face-normal mean shift with SURE (default) or the paper's pipeline.");
  denoise.def_readwrite("noise_level", &DenoiseOptions::noiseLevel)
      .def_readwrite("strength", &DenoiseOptions::strength)
      .def_readwrite("range_bandwidths", &DenoiseOptions::rangeBandwidths)
      .def_readwrite("neighborhood", &DenoiseOptions::neighborhood)
      .def_readwrite("support_smoothing", &DenoiseOptions::supportSmoothing)
      .def_readwrite("presmoothing", &DenoiseOptions::presmoothing)
      .def_readwrite("taubin_only_steps", &DenoiseOptions::taubinOnlySteps)
      .def_readwrite("candidate_taubin", &DenoiseOptions::candidateTaubin)
      .def_readwrite("taubin_only_margin", &DenoiseOptions::taubinOnlyMargin)
      .def_readwrite("light_start", &DenoiseOptions::lightStart)
      .def_readwrite("light_start_turn", &DenoiseOptions::lightStartTurn)
      .def_readwrite("blend_spread", &DenoiseOptions::blendSpread)
      .def_readwrite("max_passes", &DenoiseOptions::maxPasses)
      .def_readwrite("patience", &DenoiseOptions::patience)
      .def_readwrite("fixed_passes", &DenoiseOptions::fixedPasses)
      .def_readwrite("vertex_iterations", &DenoiseOptions::vertexIterations)
      .def_readwrite("risk_normal_smoothing", &DenoiseOptions::riskNormalSmoothing)
      .def_readwrite("probe_spacing", &DenoiseOptions::probeSpacing)
      .def_readwrite("bounded_divergence", &DenoiseOptions::boundedDivergence)
      .def_readwrite("gradient_risk_weight", &DenoiseOptions::gradientRiskWeight)
      .def_readwrite("tie_probes", &DenoiseOptions::tieProbes)
      .def_readwrite("tie_margin", &DenoiseOptions::tieMargin)
      .def_readwrite("tie_standard_errors", &DenoiseOptions::tieStandardErrors)
      .def_readwrite("tie_by_normals", &DenoiseOptions::tieByNormals)
      .def_readwrite("input_candidate", &DenoiseOptions::inputCandidate)
      .def_readwrite("spatial_order", &DenoiseOptions::spatialOrder)
      .def_readwrite("refine_noise", &DenoiseOptions::refineNoise)
      .def_readwrite("detail_bound_ratio", &DenoiseOptions::detailBoundRatio)
      .def_readwrite("high_frequency_level", &DenoiseOptions::highFrequencyLevel)
      .def_readwrite("level_lean", &DenoiseOptions::levelLean)
      .def_readwrite("high_frequency_min_samples", &DenoiseOptions::highFrequencyMinSamples)
      .def_readwrite("planar_level_share", &DenoiseOptions::planarLevelShare)
      .def_readwrite("planar_keep", &DenoiseOptions::planarKeep)
      .def_readwrite("halving_race", &DenoiseOptions::halvingRace)
      .def_readwrite("impulse_kurtosis", &DenoiseOptions::impulseKurtosis)
      .def_readwrite("impulse_shrink", &DenoiseOptions::impulseShrink)
      .def_readwrite("impulse_spectrum_kurtosis", &DenoiseOptions::impulseSpectrumKurtosis)
      .def_readwrite("impulse_spectrum_min_samples", &DenoiseOptions::impulseSpectrumMinSamples)
      .def_readwrite("impulse_spectrum_veto", &DenoiseOptions::impulseSpectrumVeto)
      .def_readwrite("seed", &DenoiseOptions::seed)
      .def_readwrite("threads", &DenoiseOptions::threads)
      .def_readwrite("paper", &DenoiseOptions::paper)
      .def_readwrite("min_piece_vertices", &DenoiseOptions::minPieceVertices)
      .def_readwrite("levels", &DenoiseOptions::levels)
      .def_readwrite("alpha", &DenoiseOptions::alpha)
      .def_readwrite("wavelet", &DenoiseOptions::wavelet);
  enumField(denoise, "preset", &DenoiseOptions::preset, {{"default", DenoisePreset::Default}, {"paper", DenoisePreset::Paper}});

  auto bilateral = optionsClass<BilateralNormalOptions>(m, "BilateralNormalOptions", "Bilateral normal filtering.");
  bilateral.def_readwrite("normal_iterations", &BilateralNormalOptions::normalIterations)
      .def_readwrite("sigma_spatial", &BilateralNormalOptions::sigmaSpatial)
      .def_readwrite("sigma_range", &BilateralNormalOptions::sigmaRange)
      .def_readwrite("vertex_update", &BilateralNormalOptions::vertexUpdate);
  enumField(bilateral, "neighborhood", &BilateralNormalOptions::neighborhood,
            {{"vertex", FaceNeighborhood::Vertex}, {"edge", FaceNeighborhood::Edge}});

  auto terrain = optionsClass<TerrainOptions>(m, "TerrainOptions", "The procedural fractal terrain.");
  terrain.def_readwrite("size", &TerrainOptions::size)
      .def_readwrite("seed", &TerrainOptions::seed)
      .def_readwrite("cell_size", &TerrainOptions::cellSize)
      .def_readwrite("relief", &TerrainOptions::relief)
      .def_readwrite("roughness", &TerrainOptions::roughness)
      .def_readwrite("forest_cover", &TerrainOptions::forestCover)
      .def_readwrite("max_vegetation_height", &TerrainOptions::maxVegetationHeight)
      .def_readwrite("water_level", &TerrainOptions::waterLevel);
}

}  // namespace geoshift::python

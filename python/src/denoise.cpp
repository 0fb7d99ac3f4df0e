// Denoising and smoothing: the denoise request (the core's denoise_request.hpp, as the CLI's
// `denoise` and the wasm op read it, so all three accept and refuse alike), bilateral normal
// filtering and Taubin smoothing with their options, and the parameter tables (params.hpp).
#include <cmath>

#include "bindings.hpp"
#include "geoshift/bilateral_normal.hpp"
#include "geoshift/denoise_request.hpp"
#include "geoshift/params.hpp"
#include "geoshift/smoothing.hpp"

namespace geoshift::python {

namespace {

// A Python value as a request's value: bool, int and float, str, a sequence of numbers (list,
// tuple, 1-D array); anything else is Unsupported, which the core refuses naming the type it wants.
ParamValue paramValueOf(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) return v.cast<double>();
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::array>(v) || py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::vector<double> numbers;
    for (const py::handle& item : v) {
      if (py::isinstance<py::bool_>(item) || py::isinstance<py::str>(item)) return Unsupported{};
      try {
        numbers.push_back(item.cast<double>());
      } catch (const py::cast_error&) {
        return Unsupported{};
      }
    }
    return numbers;
  }
  // numpy scalars
  if (py::hasattr(v, "dtype") && py::hasattr(v, "item")) return paramValueOf(v.attr("item")());
  return Unsupported{};
}

std::vector<Vec3> callerPositions(const Built& b, const Mesh& mesh) {
  std::vector<Vec3> positions(b.callerVertices());
  for (size_t i = 0; i < positions.size(); ++i) positions[i] = mesh.position(b.build.vertexOf[i]);
  return positions;
}

// The request's method on the welded mesh; the figures of the run, by method.
py::dict denoiseRequestCall(Built& b, const py::dict& params, const DenoiseOptions& base, const py::object& callback) {
  ParamValues values;
  for (auto [k, v] : params) values.emplace_back(py::str(k), paramValueOf(v));
  DenoiseSettings settings;
  settings.meanShift = base;
  settings = denoiseSettings(std::move(values), std::move(settings));
  Run run(callback);
  Mesh mesh = b.mesh();
  py::dict out;
  out["method"] = denoiseMethodName(settings.method);
  if (settings.method == DenoiseMethod::Bilateral) {
    const BilateralNormalResult r = run([&](const Progress& p) { return bilateralNormalDenoise(mesh, settings.bilateral, p); });
    out["sigma_spatial"] = r.sigmaSpatial;
    out["limited_steps"] = r.vertexUpdate.limitedSteps;
  } else if (settings.method == DenoiseMethod::Taubin) {
    run([&](const Progress& p) {
      taubinSmooth(mesh, settings.taubin, p);
      return 0;
    });
    out["iterations"] = settings.taubin.iterations;
  } else {
    const DenoiseResult r = run([&](const Progress& p) { return denoise(mesh, settings.meanShift, p); });
    out["preset"] = settings.meanShift.preset == DenoisePreset::Paper ? "paper" : "default";
    out["noise_level"] = r.noiseLevel;
    out["noise_estimated"] = r.noiseEstimated;
    out["presmoothing_steps"] = r.presmoothingSteps;
    out["passes"] = r.passes;
    out["taubin_only"] = r.taubinOnly;
    out["range_bandwidth"] = r.rangeBandwidth;
    out["passes_run"] = r.passesRun;
    out["tie_probes"] = r.tieProbes;
    out["tie_by_normals"] = r.tieByNormals;
    out["light_start_raced"] = r.lightStartRaced;
    out["light_start_turned_down"] = r.lightStartTurnedDown;
    out["estimated_error"] = r.estimatedError;
    out["impulse_garrote"] = r.impulseGarrote;
    out["kept_input"] = r.keptInput;
    out["planar_level"] = r.planarLevel;
    out["planar_kept"] = r.planarKept;
    out["blend_weight"] = r.blend.weight;
    out["blend_steps"] = r.blend.presmoothingSteps;
    out["blend_passes"] = r.blend.passes;
    out["blend_taubin_only"] = r.blend.taubinOnly;
    out["blend_range_bandwidth"] = r.blend.rangeBandwidth;
    out["start_blend_weight"] = r.startBlend.weight;
    out["start_blend_steps"] = r.startBlend.presmoothingSteps;
    out["start_blend_passes"] = r.startBlend.passes;
    out["start_blend_range_bandwidth"] = r.startBlend.rangeBandwidth;
    out["displacement_kurtosis"] = r.displacementKurtosis;
    out["spectrum_kurtosis"] = r.spectrumKurtosis;
    out["mean_iterations"] = r.meanIterations;
    out["converged_fraction"] = r.convergedFraction;
    out["kept_pieces"] = r.keptPieces;
    out["kept_vertices"] = r.keptVertices;
    out["limited_steps"] = r.limitedSteps;
    out["threads"] = r.threads;
    out["filtered_vertices"] = r.filteredVertices;
    out["seconds"] = r.seconds;
  }
  out["positions"] = fromPoints(callerPositions(b, mesh));
  return out;
}

py::object valueToPython(const ParamValue& v) {
  if (const bool* x = std::get_if<bool>(&v)) return py::bool_(*x);
  if (const double* x = std::get_if<double>(&v)) return py::float_(*x);
  if (const std::string* x = std::get_if<std::string>(&v)) return py::str(*x);
  if (const std::vector<double>* x = std::get_if<std::vector<double>>(&v)) {
    if (x->size() == 1) return py::float_(x->front());
    return py::cast(*x);
  }
  return py::none();
}

py::dict conditionToPython(const ParamCondition& c) {
  py::dict out;
  for (const auto& [name, values] : c) out[py::str(name)] = values;
  return out;
}

// The tables in the shape of the wasm module's paramSpecs() (wasm/param_specs.cpp).
py::dict paramSpecsToPython() {
  static const char* const types[] = {"number", "integer", "boolean", "enum", "string"};
  py::dict out;
  for (const OpParamSpecs& op : paramSpecs()) {
    py::dict params;
    for (const ParamSpec& s : op.params) {
      py::dict d;
      d["type"] = types[static_cast<int>(s.type)];
      d["doc"] = s.doc;
      if (s.defaultValue) d["default"] = valueToPython(*s.defaultValue);
      if (s.min && std::isfinite(*s.min)) d["min"] = *s.min;
      if (s.max && std::isfinite(*s.max)) d["max"] = *s.max;
      if (s.minExclusive) d["minExclusive"] = true;
      if (!s.values.empty()) d["values"] = s.values;
      if (s.list) d["list"] = true;
      if (!s.appliesWhen.empty()) {
        py::list when;
        for (const ParamCondition& c : s.appliesWhen) when.append(conditionToPython(c));
        d["when"] = when;
      }
      if (!s.cases.empty()) {
        py::list cases;
        for (const ParamCase& c : s.cases) {
          py::dict e;
          e["when"] = conditionToPython(c.when);
          if (c.defaultValue) e["default"] = valueToPython(*c.defaultValue);
          if (c.min && std::isfinite(*c.min)) e["min"] = *c.min;
          if (c.max && std::isfinite(*c.max)) e["max"] = *c.max;
          cases.append(e);
        }
        d["cases"] = cases;
      }
      params[py::str(s.name)] = d;
    }
    py::dict entry;
    entry["doc"] = op.doc;
    entry["params"] = params;
    out[py::str(op.op)] = entry;
  }
  return out;
}

}  // namespace

void bindDenoising(py::module_& m) {
  m.def("_denoise", &denoiseRequestCall, py::arg("built"), py::arg("params"), py::arg("base"), py::arg("progress"));
  m.def("_param_specs", &paramSpecsToPython);

  m.def("_bilateral", [](Built& b, const BilateralNormalOptions& options, const py::object& callback) {
    Run run(callback);
    Mesh mesh = b.mesh();
    const BilateralNormalResult r = run([&](const Progress& p) { return bilateralNormalDenoise(mesh, options, p); });
    py::dict out;
    out["positions"] = fromPoints(callerPositions(b, mesh));
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
    return fromPoints(callerPositions(b, mesh));
  });
}

}  // namespace geoshift::python

// loadMesh / setAttribute / freeMesh / run / ops: the session API of the module (see adapters.hpp).
#include <atomic>
#include <thread>

#include <emscripten/emscripten.h>

#include "adapters.hpp"
#include "convert.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/params.hpp"
#include "geoshift/presets.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

using emscripten::val;

namespace {

void setOptionalSignal(Session& session, const val& extras, const char* key, const char* name) {
  if (extras.isUndefined() || extras.isNull()) return;
  const val array = extras[key];
  if (array.isUndefined() || array.isNull()) return;
  const std::size_t n = static_cast<std::size_t>(session.callerVertexCount());
  if (!isA(array, "Float32Array")) throw InputError(std::string(key) + " must be a Float32Array");
  const auto length = array["length"].as<std::size_t>();
  // glTF colors may carry alpha; the filters use RGB only.
  const int dim = length == 4 * n && n > 0 && std::string(key) == "colors" ? 4 : 3;
  std::vector<double> values = readFloats(array, dim * n, key);
  if (dim == 4) {
    std::vector<double> rgb(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) rgb[3 * i + c] = values[4 * i + c];
    }
    values = std::move(rgb);
  }
  setCallerAttribute(session, name, 3, values);
}

val positionsOut(const Session& s) {
  std::vector<float> xyz(3 * s.build.vertexOf.size());
  for (std::size_t i = 0; i < s.build.vertexOf.size(); ++i) {
    const Vec3& p = s.build.mesh.position(s.build.vertexOf[i]);
    for (int c = 0; c < 3; ++c) xyz[3 * i + c] = static_cast<float>(p[c]);
  }
  return copyOut("Float32Array", xyz);
}

}  // namespace

val loadMesh(const val& positions, const val& indices, const val& extras) {
  return guarded([&] {
    Session session;
    session.build = buildMesh(readSoup(positions, indices));
    session.attributes = AttributeSet(session.build.mesh.vertexCount());
    setOptionalSignal(session, extras, "colors", "color");
    setOptionalSignal(session, extras, "normals", "normal");

    val result = val::object();
    result.set("ok", true);
    result.set("vertexCount", session.callerVertexCount());
    result.set("weldedVertexCount", session.build.mesh.vertexCount());
    result.set("faceCount", session.build.mesh.faceCount());
    result.set("vertexOf", copyOut("Int32Array", session.build.vertexOf));
    result.set("averageEdgeLength", averageEdgeLength(session.build.mesh));
    result.set("report", reportToJs(session.build.report));
    result.set("handle", sessions().add(std::move(session)));
    return result;
  });
}

val setAttribute(int handle, const std::string& name, int dim, const val& values) {
  return guarded([&] {
    Session& s = sessions().get(handle);
    if (dim < 1 || dim > 16) throw InputError("setAttribute \"" + name + "\": dim must be 1 to 16");
    setCallerAttribute(s, name, dim, readFloats(values, static_cast<std::size_t>(dim) * s.callerVertexCount(), name));
    val result = val::object();
    result.set("ok", true);
    return result;
  });
}

bool freeMesh(int handle) { return sessions().remove(handle); }

val listOps() {
  val names = val::array();
  for (const OpEntry& e : opTable()) names.call<void>("push", std::string(e.name));
  return names;
}

val listPresets() {
  val list = val::array();
  for (const FilterPreset& p : filterPresets()) {
    const MeanShiftOptions& o = p.options;
    val entry = val::object();
    entry.set("name", p.name);
    entry.set("description", p.description);
    entry.set("signal", p.signal);
    // In the filter op's parameter names and units, so that a preset is a parameter object.
    entry.set("mode", std::string(o.passes > 1 ? "bms" : "ms"));
    entry.set("passes", o.passes);
    entry.set("hs", o.spatialBandwidth);
    entry.set("hr", o.rangeBandwidth);
    entry.set("radius", o.radius > 0 ? o.radius : 3 * o.spatialBandwidth);
    entry.set("eps", o.epsilon);
    entry.set("kmax", o.maxIterations);
    entry.set("rangeUpdate", std::string(o.rangeUpdate == RangeUpdate::Sampled ? "sampled" : "joint"));
    entry.set("levels", p.levels);
    entry.set("alpha", p.detailGain);
    list.call<void>("push", entry);
  }
  // The default denoiser's settings in the denoise op's parameter names, from its table (the core's
  // params.hpp), so that the app's Denoise preset shows the library's defaults.
  const ParamRequest defaults(paramSpecsOf("denoise"), {});
  val denoise = val::object();
  denoise.set("name", std::string("denoise"));
  denoise.set("description", std::string("the default denoiser (docs/denoising.md)"));
  denoise.set("signal", std::string("normal"));
  for (const char* name : {"strength", "noise", "passes", "radius", "hs", "vertexIterations", "lightStart", "levels", "alpha"})
    denoise.set(name, defaults.number(name));
  denoise.set("impulse", defaults.text("impulse"));
  // Several candidate h_r by default: the app shows 0 (Auto), which the op reads as those.
  const std::vector<double> hr = defaults.numbers("hr");
  denoise.set("hr", hr.size() == 1 ? hr.front() : 0.0);
  list.call<void>("push", denoise);
  return list;
}

val run(int handle, const std::string& op, const val& params, const val& onProgress) {
  return guarded([&] {
    Session& session = sessions().get(handle);
    const OpEntry& entry = findOp(op);
    const ParamRequest request(paramSpecsOf(entry.name), paramValuesOf(entry.name, params));

    JsProgress js(onProgress);
    const Progress& progress = js.progress;

    const double start = emscripten_get_now();
    const OpContext context{session, request, progress};
    OpOutput output = entry.run(context);
    progress.step(1, "copying results");
    const double elapsed = emscripten_get_now() - start;

    // Commit: from here on nothing throws but bad_alloc, and the session stays consistent even then
    // (each assignment is whole).
    const std::vector<int>& vertexOf = session.build.vertexOf;
    val result = val::object();
    result.set("ok", true);
    if (output.positions) {
      session.build.mesh.positions() = std::move(*output.positions);
      result.set("positions", positionsOut(session));
    }
    if (output.colors) {
      result.set("colors", floatsOut(toCallerLayout(*output.colors, 3, vertexOf)));
      if (output.colorsAreSignal) session.attributes.set("color", 3, AttributeKind::Euclidean, std::move(*output.colors));
    }
    if (output.normals) {
      result.set("normals", floatsOut(toCallerLayout(*output.normals, 3, vertexOf)));
      session.attributes.set("normal", 3, AttributeKind::UnitVector, std::move(*output.normals));
    }
    val scalars = val::object();
    for (auto& [name, values] : output.scalars) {
      scalars.set(name, floatsOut(toCallerLayout(values, 1, vertexOf)));
      session.attributes.set(name, 1, AttributeKind::Euclidean, std::move(values));
    }
    result.set("scalars", scalars);
    val stats = output.stats;
    stats.set("op", op);
    stats.set("timeMs", elapsed);
    stats.set("vertices", session.callerVertexCount());
    stats.set("weldedVertices", session.build.mesh.vertexCount());
    stats.set("threadsAvailable", context.threads(0));
    result.set("stats", stats);
    return result;
  });
}

val loadMeshWithoutExtras(const val& positions, const val& indices) { return loadMesh(positions, indices, val::undefined()); }

val runWithoutProgress(int handle, const std::string& op, const val& params) {
  return run(handle, op, params, val::undefined());
}

}  // namespace geoshift::wasm

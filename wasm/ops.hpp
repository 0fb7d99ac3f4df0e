#pragma once
// Operations that `run(handle, op, params, onProgress)` dispatches to.
//
// Adding an op: add its parameter table to core/src/param_specs.cpp (names, types, defaults,
// ranges: the only place that knows them), write wasm/ops_NAME.cpp defining `OpOutput
// runNAME(const OpContext&)`, declare it below, and add one line to the table in ops.cpp.
// wasm/CMakeLists.txt picks up every wasm/*.cpp; the npm package's option types are generated from
// the tables (paramSpecs(); package/scripts/generate-options.mjs). An op never changes the session
// itself: it works on copies and returns what changed; the dispatcher commits that only when the op
// succeeded.
#include <atomic>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <emscripten/val.h>

#include "geoshift/params.hpp"
#include "geoshift/progress.hpp"
#include "session.hpp"

namespace geoshift::wasm {

// The Progress of a call from JavaScript (run, preview). Only the calling thread may touch JS
// values: the core's worker threads report through the cancel flag alone. onProgress(fraction,
// stage), when it is a function, is called on the calling thread; its answer true raises the flag,
// which every thread sees at its next step. Not copyable: `progress` refers to this object.
struct JsProgress {
  explicit JsProgress(const emscripten::val& onProgress)
      : callback(onProgress), hasCallback(onProgress.typeOf().as<std::string>() == "function") {
    progress.cancel = &cancel;
    progress.report = [this](double fraction, std::string_view stage) {
      if (!hasCallback || std::this_thread::get_id() != caller) return;
      if (callback(fraction, std::string(stage)).isTrue()) cancel.store(true, std::memory_order_relaxed);
    };
  }
  JsProgress(const JsProgress&) = delete;
  JsProgress& operator=(const JsProgress&) = delete;

  std::atomic<bool> cancel{false};
  const emscripten::val& callback;
  const bool hasCallback;
  const std::thread::id caller = std::this_thread::get_id();
  Progress progress;
};

struct OpContext {
  const Session& session;
  // The op's parameters, checked against its table in the core (params.hpp) before the op runs:
  // read them by name, with the table's defaults.
  const ParamRequest& params;
  // Report at least every ~100 ms; step() throws Cancelled once the caller asked to stop.
  const Progress& progress;
  // Worker threads an op may start for `requested` (0 = as many as the machine has): 1 in the
  // single-threaded build, and never more than the pthread pool holds in the threaded one (a
  // thread beyond the pool would wait for a worker the blocked caller can never start).
  int threads(int requested) const;
};

struct OpOutput {
  // New positions of the welded mesh's vertices, when the op moved them.
  std::optional<std::vector<Vec3>> positions;
  // RGB per welded vertex (linear, [0,1]). `colorsAreSignal`: they replace the "color" signal
  // (a color filter); otherwise they only visualise something (a curvature color map).
  std::optional<std::vector<double>> colors;
  bool colorsAreSignal = false;
  // Unit normals per welded vertex (a normal filter); they replace the "normal" signal.
  std::optional<std::vector<double>> normals;
  // Named per-welded-vertex scalars (e.g. "_CURVATURE", "_SEGMENT"); kept as signals of the session.
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  // Numbers worth showing after a run (iterations, ...); the dispatcher adds timing and counts.
  emscripten::val stats = emscripten::val::object();
};

using OpFunction = OpOutput (*)(const OpContext&);

struct OpEntry {
  const char* name;  // also the name of its parameter table, paramSpecsOf(name)
  OpFunction run;
};

const std::vector<OpEntry>& opTable();

// The op of that name; InputError naming the ops this build knows for another.
const OpEntry& findOp(const std::string& op);

// A JS parameter object (undefined or null: no parameters) as the values of a request of `op`:
// numbers, booleans, strings and arrays of numbers as they are, anything else as Unsupported (the
// core's check names the type it wants). InputError when it is not an object.
ParamValues paramValuesOf(const std::string& op, const emscripten::val& params);

OpOutput runNoise(const OpContext&);      // ops_noise.cpp
OpOutput runSmooth(const OpContext&);     // ops_smooth.cpp
OpOutput runCurvature(const OpContext&);  // ops_curvature.cpp
OpOutput runGeodesic(const OpContext&);   // ops_geodesic.cpp
OpOutput runFilter(const OpContext&);     // ops_filter.cpp
OpOutput runDenoise(const OpContext&);    // ops_denoise.cpp
OpOutput runWavelet(const OpContext&);    // ops_wavelet.cpp

}  // namespace geoshift::wasm

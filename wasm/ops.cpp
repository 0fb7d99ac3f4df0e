// The op table and JS parameter objects as requests. One line per op; see ops.hpp for how to add one.
#include "ops.hpp"

#include <algorithm>
#include <thread>

#include "geoshift/error.hpp"

#ifdef __EMSCRIPTEN_PTHREADS__
#include <emscripten/emscripten.h>
// Workers in the pool (idle or running); threads beyond it cannot start while the caller blocks.
EM_JS(int, geoshift_pthread_pool_size, (), {
  return PThread.unusedWorkers.length + PThread.runningWorkers.length;
});
#endif

namespace geoshift::wasm {

const std::vector<OpEntry>& opTable() {
  static const std::vector<OpEntry> table = {
      {"noise", runNoise},   {"smooth", runSmooth}, {"curvature", runCurvature}, {"geodesic", runGeodesic},
      {"filter", runFilter}, {"denoise", runDenoise}, {"wavelet", runWavelet},
  };
  return table;
}

const OpEntry& findOp(const std::string& op) {
  std::string known;
  for (const OpEntry& e : opTable()) {
    if (op == e.name) return e;
    known += (known.empty() ? "" : ", ") + std::string(e.name);
  }
  throw InputError("unknown op \"" + op + "\" (this build knows " + known + ")");
}

int OpContext::threads(int requested) const {
#ifdef __EMSCRIPTEN_PTHREADS__
  int n = requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency());
  const int pool = geoshift_pthread_pool_size();
  if (n > pool) n = pool;
  return n < 1 ? 1 : n;
#else
  (void)requested;
  return 1;
#endif
}

using emscripten::val;

namespace {

ParamValue paramValueOf(const val& v) {
  const std::string type = v.typeOf().as<std::string>();
  if (type == "number") return v.as<double>();
  if (type == "boolean") return v.as<bool>();
  if (type == "string") return v.as<std::string>();
  if (val::global("Array").call<bool>("isArray", v)) {
    std::vector<double> numbers;
    const int n = v["length"].as<int>();
    for (int i = 0; i < n; ++i) {
      const val item = v[i];
      if (item.typeOf().as<std::string>() != "number") return Unsupported{};
      numbers.push_back(item.as<double>());
    }
    return numbers;
  }
  return Unsupported{};
}

}  // namespace

ParamValues paramValuesOf(const std::string& op, const val& params) {
  if (params.isUndefined() || params.isNull()) return {};
  if (params.typeOf().as<std::string>() != "object") throw InputError(op + ": params must be an object");
  const OpParamSpecs& specs = paramSpecsOf(op);
  ParamValues values;
  const val keys = val::global("Object").call<val>("keys", params);
  const int count = keys["length"].as<int>();
  for (int i = 0; i < count; ++i) {
    const std::string key = keys[i].as<std::string>();
    const val v = params[key];
    // An explicit undefined of a known parameter is no value (spreads of optional fields make them).
    const bool known = std::any_of(specs.params.begin(), specs.params.end(), [&](const ParamSpec& s) { return s.name == key; });
    if (v.isUndefined() && known) continue;
    values.emplace_back(key, paramValueOf(v));
  }
  return values;
}

}  // namespace geoshift::wasm

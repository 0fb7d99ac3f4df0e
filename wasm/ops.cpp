// The op table and the parameter reader. One line per op; see ops.hpp for how to add one.
#include "ops.hpp"

#include <cmath>
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
      {"noise", runNoise, {"amount", "distribution", "direction", "seed"}},
      {"smooth", runSmooth, {"iterations", "lambda", "mu", "weights"}},
      {"curvature", runCurvature, {"kind"}},
      {"geodesic", runGeodesic, {"source", "radius"}},
      {"filter", runFilter, {"signal", "mode", "passes", "hs", "hr", "radius", "kmax", "eps", "rangeUpdate", "segments", "threads", "levels", "alpha", "filterGeometry"}},
      {"denoise", runDenoise, {"method", "preset", "noise", "strength", "hs", "hr", "radius", "kmax", "eps", "passes", "vertexIterations", "rangeUpdate", "faceNormals", "threads", "supportIterations", "normalIterations", "sigmaC", "sigmaS", "neighbors", "iterations", "lambda", "mu", "levels", "alpha"}},
  };
  return table;
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

val Params::get(const char* name) const {
  if (object_.isUndefined() || object_.isNull()) return val::undefined();
  return object_[name];
}

bool Params::has(const char* name) const { return !get(name).isUndefined(); }

double Params::number(const char* name, double fallback, double min, double max) const {
  const val v = get(name);
  if (v.isUndefined()) return fallback;
  if (v.typeOf().as<std::string>() != "number") {
    throw InputError(op_ + ": parameter " + name + " must be a number");
  }
  const double x = v.as<double>();
  if (!std::isfinite(x) || x < min || x > max) {
    throw InputError(op_ + ": parameter " + name + " = " + std::to_string(x) + " is outside [" +
                     std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return x;
}

int Params::integer(const char* name, int fallback, int min, int max) const {
  const double x = number(name, fallback, min, max);
  if (x != std::floor(x)) throw InputError(op_ + ": parameter " + name + " must be a whole number");
  return static_cast<int>(x);
}

bool Params::flag(const char* name, bool fallback) const {
  const val v = get(name);
  if (v.isUndefined()) return fallback;
  if (v.typeOf().as<std::string>() != "boolean") throw InputError(op_ + ": parameter " + name + " must be true or false");
  return v.as<bool>();
}

std::string Params::text(const char* name, const std::string& fallback) const {
  const val v = get(name);
  if (v.isUndefined()) return fallback;
  if (v.typeOf().as<std::string>() != "string") throw InputError(op_ + ": parameter " + name + " must be a string");
  return v.as<std::string>();
}

std::string Params::choice(const char* name, const std::string& fallback, const std::vector<std::string>& choices) const {
  const std::string s = text(name, fallback);
  for (const std::string& c : choices) {
    if (c == s) return s;
  }
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
  throw InputError(op_ + ": parameter " + name + " = \"" + s + "\" is not one of " + list);
}

}  // namespace geoshift::wasm

#pragma once
// Conversions between JS values and core types shared by the adapters: typed arrays are checked
// at the edge (a wrong array type would otherwise be converted silently) and copied in or out once,
// so JS never holds a view into a heap that a later memory growth would detach.
#include <string>
#include <vector>

#include <emscripten/val.h>

#include "geoshift/mesh.hpp"

namespace geoshift::wasm {

emscripten::val failure(const std::string& message);
bool isA(const emscripten::val& value, const char* type);

// `new Float32Array(view)` copies, and the view into the heap dies with this expression.
template <class T>
emscripten::val copyOut(const char* arrayType, const std::vector<T>& values) {
  return emscripten::val::global(arrayType).new_(emscripten::typed_memory_view(values.size(), values.data()));
}
// Doubles of the core as a Float32Array, the type of the GL buffers they feed.
emscripten::val floatsOut(const std::vector<double>& values);

// Checks types and lengths (multiples of 3) and copies; throws InputError naming the problem.
TriangleSoup readSoup(const emscripten::val& positions, const emscripten::val& indices);
// A Float32Array (or any typed array of numbers) of exactly `count` numbers; `what` names it.
std::vector<double> readFloats(const emscripten::val& array, std::size_t count, const std::string& what);

emscripten::val reportToJs(const BuildReport& report);

// Runs `body`, turning the core's exceptions into { ok: false, error[, cancelled] }.
template <class Body>
emscripten::val guarded(Body body);

}  // namespace geoshift::wasm

#include "convert_guard.hpp"

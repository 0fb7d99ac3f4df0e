// Registrations only; the adapters that turn typed arrays into core calls live in api.cpp,
// preview.cpp, read_file.cpp and param_specs.cpp, the ops in ops_*.cpp, and the TypeScript view of
// these exports is package/src/module.ts.
#include <emscripten/bind.h>

#include "adapters.hpp"

EMSCRIPTEN_BINDINGS(geoshift) {
  emscripten::function("loadMesh", &geoshift::wasm::loadMesh);
  emscripten::function("loadMesh", &geoshift::wasm::loadMeshWithoutExtras);
  emscripten::function("setAttribute", &geoshift::wasm::setAttribute);
  emscripten::function("freeMesh", &geoshift::wasm::freeMesh);
  emscripten::function("run", &geoshift::wasm::run);
  emscripten::function("run", &geoshift::wasm::runWithoutProgress);
  emscripten::function("preview", &geoshift::wasm::preview);
  emscripten::function("preview", &geoshift::wasm::previewWithoutProgress);
  emscripten::function("readFile", &geoshift::wasm::readFile);
  emscripten::function("readFile", &geoshift::wasm::readFileWithDefaultLimit);
  emscripten::function("readFile", &geoshift::wasm::readFileWithArrays);
  emscripten::function("ops", &geoshift::wasm::listOps);
  emscripten::function("presets", &geoshift::wasm::listPresets);
  emscripten::function("paramSpecs", &geoshift::wasm::listParamSpecs);
}

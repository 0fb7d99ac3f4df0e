// Registrations only; the adapters that turn typed arrays into core calls live in adapters.cpp,
// and the TypeScript view of these exports is geoshift.d.ts.
#include <emscripten/bind.h>

#include "adapters.hpp"

EMSCRIPTEN_BINDINGS(geoshift) {
  emscripten::function("processMesh", &geoshift::wasm::processMesh);
}

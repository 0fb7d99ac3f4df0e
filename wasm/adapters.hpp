#pragma once
// Adapters between JS values and the core: typed arrays are copied in once and out once, and every
// failure comes back as a value ({ ok: false, error }) instead of a C++ exception, so the JS side
// never needs exception support or `delete()` calls. Types are declared in geoshift.d.ts.
#include <emscripten/val.h>

namespace geoshift::wasm {

// processMesh(positions: Float32Array [x0 y0 z0 x1 ...], indices: Uint32Array [a0 b0 c0 ...]):
// welds and builds the mesh, computes the discrete curvatures and returns a ProcessMeshResult.
// Never throws: bad arguments and the core's InputError messages come back as { ok: false, error }.
emscripten::val processMesh(const emscripten::val& positions, const emscripten::val& indices);

}  // namespace geoshift::wasm

#pragma once
// Adapters between JS values and the core: typed arrays are copied in once and out once, and every
// failure comes back as a value ({ ok: false, error }) instead of a C++ exception, so the JS side
// never needs exception support or `delete()` calls. Types are declared in package/src/module.ts.
#include <string>

#include <emscripten/val.h>

namespace geoshift::wasm {

// loadMesh(positions: Float32Array [x0 y0 z0 x1 ...], indices: Uint32Array [a0 b0 c0 ...],
// extras?: { colors?: Float32Array (3 or 4 per vertex), normals? }): welds and builds a mesh the
// module keeps; returns { ok, handle, counts, vertexOf, averageEdgeLength, report }. Never throws:
// bad arguments and the core's InputError messages come back as { ok: false, error }.
emscripten::val loadMesh(const emscripten::val& positions, const emscripten::val& indices, const emscripten::val& extras);

// setAttribute(handle, name, dim, values: Float32Array of dim per caller vertex): adds or replaces a
// signal ("color", "normal", "_CURVATURE", a terrain attribute...). Returns { ok } or a failure.
emscripten::val setAttribute(int handle, const std::string& name, int dim, const emscripten::val& values);

// freeMesh(handle): forgets a mesh; true when it existed.
bool freeMesh(int handle);

// run(handle, op, params, onProgress?): runs one op of the table in ops.cpp. onProgress(fraction,
// stage) is called from the calling thread at least every ~100 ms of work; returning true asks the
// run to stop, which then fails with { ok: false, cancelled: true }. On success returns { ok: true,
// positions?, colors?, scalars: { name: Float32Array }, stats } in the caller's vertex layout and
// keeps the new positions and signals for the next run.
emscripten::val run(int handle, const std::string& op, const emscripten::val& params, const emscripten::val& onProgress);

// The same without the optional last argument: embind checks the argument count exactly, so the
// optional arguments of the JS API are overloads by count.
emscripten::val loadMeshWithoutExtras(const emscripten::val& positions, const emscripten::val& indices);
emscripten::val runWithoutProgress(int handle, const std::string& op, const emscripten::val& params);

// preview(handle, op, params, maxVertices, onProgress?): the op run on a coarse wavelet level of the
// mesh (at most maxVertices vertices, analysed once and kept with the session) and brought back to
// every vertex; returns what run returns, with stats.previewVertices, levels, stages, analysisMs,
// analysisReused and coarseOpMs, and leaves the session as it was (preview.cpp).
emscripten::val preview(int handle, const std::string& op, const emscripten::val& params, int maxVertices, const emscripten::val& onProgress);
emscripten::val previewWithoutProgress(int handle, const std::string& op, const emscripten::val& params, int maxVertices);

// readFile(name, bytes: Uint8Array, maxVertices?): the core's readers (readDocument) on a file's
// bytes, the name choosing the format by extension as in the CLI; each part is also built as the
// filters build it. Returns { ok: true, parts: [{ label, vertices, triangles, instances, report }],
// vertices, triangles, warnings } or { ok: false, error[, outOfMemory] } with the CLI's message
// (read_file.cpp). Nothing of the file is kept.
emscripten::val readFile(const std::string& name, const emscripten::val& bytes, double maxVertices);
// The same (maxVertices 0: the CLI's limit), and with withArrays each part also carries its arrays in the file's vertex order:
// positions (Float32Array), indices (Uint32Array), normals? , colors? (RGBA), attributes (name ->
// Float32Array of dim per vertex) and transforms (Float64Array, 16 per instance, column-major).
emscripten::val readFileWithArrays(const std::string& name, const emscripten::val& bytes, double maxVertices, bool withArrays);
// The same with the CLI's default limit (ReadOptions::maxVertices).
emscripten::val readFileWithDefaultLimit(const std::string& name, const emscripten::val& bytes);

// ops(): the names of the ops this build knows (the web app asks before offering a preset).
emscripten::val listOps();

// paramSpecs(): every op's parameter table (the core's params.hpp) as plain JS data: types,
// defaults, ranges, choices, docs and the methods or presets each applies to (param_specs.cpp).
emscripten::val listParamSpecs();

// presets(): the core's filter presets (filterPresets()) as parameter objects of the filter op,
// with name, description and signal; the web app takes its preset values from here.
emscripten::val listPresets();

}  // namespace geoshift::wasm

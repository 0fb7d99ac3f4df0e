#pragma once
// guarded(): the one place where C++ exceptions become values for JS.
#include <new>
#include <stdexcept>

#include "geoshift/error.hpp"

namespace geoshift::wasm {

template <class Body>
emscripten::val guarded(Body body) {
  try {
    return body();
  } catch (const Cancelled&) {
    emscripten::val result = failure("cancelled");
    result.set("cancelled", true);
    return result;
  } catch (const InputError& e) {
    return failure(e.what());
  } catch (const std::bad_alloc&) {
    emscripten::val result = failure("out of memory: the mesh is too large for the 4 GB WebAssembly heap");
    result.set("outOfMemory", true);
    return result;
  } catch (const std::exception& e) {
    return failure(std::string("internal error: ") + e.what());
  } catch (...) {
    return failure("internal error: unknown exception");
  }
}

}  // namespace geoshift::wasm

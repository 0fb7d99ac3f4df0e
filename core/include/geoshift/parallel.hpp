#pragma once
// One small parallel-for over an index range, for the per-vertex filters.
//
// Work is handed out in fixed-size chunks from an atomic counter, so which thread runs an index
// changes from run to run: callers make each index's result depend on the index alone (own
// buffers per worker, no shared accumulation) and results are then identical for any thread count.
//
// The calling thread works too and is the only one that reports progress, so a progress callback
// never runs on another thread (the wasm build's callbacks into JavaScript must stay on the
// worker that made the call). Without threads (single-threaded wasm, threads = 1) it runs serially.
#include <string_view>
#include <type_traits>

#include "geoshift/progress.hpp"

namespace geoshift {

struct ParallelOptions {
  int threads = 0;        // 0: all hardware threads; clamped to [1, hardware threads]
  int chunk = 16;         // indices per hand-out: small enough that cancel and progress stay prompt
  double reportSeconds = 0.1;  // progress at least this often, when the work is that long
  // The kernels in their portable form only, even where a processor's wider instructions are used by
  // default (the face normal shift's AVX2 form on x86-64): the same bits either way; for tests.
  bool portableKernels = false;
};

// The number of threads a call with `requested` would use (0 = all).
int resolveThreads(int requested);

// Calls body(index, worker) for every index in [0, count), worker in [0, threads): at most one call
// at a time per worker, so body may use per-worker scratch. Progress reports fractions
// [from, to] of the whole under `stage` and the cancel flag is checked between chunks; the first
// exception thrown by any body (or Cancelled) stops the remaining chunks and is rethrown here once
// every worker has stopped.
template <class Body>
void parallelFor(int count, const ParallelOptions& options, const Progress& progress, std::string_view stage,
                 double from, double to, Body&& body);

namespace detail {
// Type-erased worker loop (parallel.cpp): runs `run(begin, end, worker)` chunk by chunk.
struct ChunkRunner {
  void* context;
  void (*run)(void* context, int begin, int end, int worker);
};
void parallelForChunks(int count, const ParallelOptions& options, const Progress& progress,
                       std::string_view stage, double from, double to, ChunkRunner runner);
}  // namespace detail

template <class Body>
void parallelFor(int count, const ParallelOptions& options, const Progress& progress, std::string_view stage,
                 double from, double to, Body&& body) {
  auto run = [](void* context, int begin, int end, int worker) {
    Body& b = *static_cast<std::remove_reference_t<Body>*>(context);
    for (int i = begin; i < end; ++i) b(i, worker);
  };
  detail::parallelForChunks(count, options, progress, stage, from, to,
                            detail::ChunkRunner{const_cast<void*>(static_cast<const void*>(&body)), run});
}

}  // namespace geoshift

#include "geoshift/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

// Emscripten without -pthread links std::thread but cannot start one: run serially there.
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define GEOSHIFT_NO_THREADS 1
#endif

namespace geoshift {

int resolveThreads(int requested) {
#ifdef GEOSHIFT_NO_THREADS
  (void)requested;
  return 1;
#else
  const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (requested <= 0) return hardware;
  return std::min(requested, hardware);
#endif
}

namespace detail {

void parallelForChunks(int count, const ParallelOptions& options, const Progress& progress,
                       std::string_view stage, double from, double to, ChunkRunner runner) {
  if (count <= 0) return;
  const int chunk = std::max(1, options.chunk);
  const int chunks = (count + chunk - 1) / chunk;

  std::atomic<int> next{0};
  std::atomic<int> done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::mutex failureMutex;

  const auto fail = [&](std::exception_ptr e) {
    std::lock_guard<std::mutex> lock(failureMutex);
    if (!failure) failure = e;
    stop.store(true);
  };
  // Workers other than the caller only watch the cancel flag; the caller turns it into Cancelled.
  const auto work = [&](int worker, bool caller) {
    using Clock = std::chrono::steady_clock;
    auto lastReport = Clock::now();
    const auto interval = std::chrono::duration<double>(options.reportSeconds);
    try {
      for (;;) {
        if (stop.load(std::memory_order_relaxed)) return;
        if (progress.cancelled()) {
          if (caller) progress.step(from, stage);  // throws Cancelled
          stop.store(true);
          return;
        }
        const int c = next.fetch_add(1, std::memory_order_relaxed);
        if (c >= chunks) return;
        const int begin = c * chunk, end = std::min(count, begin + chunk);
        runner.run(runner.context, begin, end, worker);
        const int finished = done.fetch_add(end - begin, std::memory_order_relaxed) + (end - begin);
        if (caller && Clock::now() - lastReport >= interval) {
          lastReport = Clock::now();
          progress.step(from + (to - from) * finished / count, stage);
        }
      }
    } catch (...) {
      fail(std::current_exception());
    }
  };

#ifdef GEOSHIFT_NO_THREADS
  work(0, true);
#else
  const int threads = std::min(resolveThreads(options.threads), chunks);
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  try {
    for (int w = 1; w < threads; ++w) pool.emplace_back(work, w, false);
  } catch (...) {
    // Could not start a thread (a full wasm pthread pool, resource limits): the ones running and
    // the caller finish the work; the results do not depend on the thread count.
  }
  work(0, true);
  for (std::thread& t : pool) t.join();
#endif
  if (failure) std::rethrow_exception(failure);
  if (progress.cancelled()) progress.step(from, stage);  // a worker saw it first
  progress.step(to, stage);
}

}  // namespace detail
}  // namespace geoshift

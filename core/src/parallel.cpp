#include "geoshift/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

// Emscripten without -pthread links std::thread but cannot start one: run serially there.
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define GEOSHIFT_NO_THREADS 1
#endif
#if !defined(GEOSHIFT_NO_THREADS) && !defined(__EMSCRIPTEN__) && (defined(__unix__) || defined(__APPLE__))
#include <pthread.h>
#define GEOSHIFT_AT_FORK 1
#endif

namespace geoshift {

int resolveThreads(int requested) {
#ifdef GEOSHIFT_NO_THREADS
  (void)requested;
  return 1;
#else
  // Read once: each read is a system call natively and, in Node's wasm, os.cpus() (0.3 ms: 1% of a
  // denoise, which resolves its threads some 2,000 times).
  static const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (requested <= 0) return hardware;
  return std::min(requested, hardware);
#endif
}

namespace {

#ifndef GEOSHIFT_NO_THREADS
// Helper threads kept from one parallelFor to the next. A denoise makes about 20 calls a pass (the
// vertex update's iterations), 1,800 on the 144k-vertex benchmark: starting and joining threads for
// each was measurable natively and more in the browser, where every start is a message to a pooled
// web worker (docs/denoising.md#speed-and-memory). One call at a time uses the pool; a call made
// meanwhile from another thread starts its own threads as before, and a call from inside a pooled
// call's body runs on its caller alone (results do not depend on the thread count).
class HelperPool {
 public:
  // Runs job(h) on helpers h = 1 .. helpers (starting helpers as needed) while the caller runs
  // job(0); returns when all have returned. False, having run nothing, when the pool is in use by
  // another thread. Fewer helpers take part when no more threads can be started.
  bool run(int helpers, const std::function<void(int)>& job) {
    std::unique_lock<std::mutex> inUse(inUse_, std::try_to_lock);
    if (!inUse.owns_lock()) return false;
    try {
      while (static_cast<int>(threads_.size()) < helpers) {
        const int index = static_cast<int>(threads_.size()) + 1;
        threads_.emplace_back([this, index] { helperLoop(index); });
      }
    } catch (...) {
      // Could not start a thread (a full wasm pthread pool, resource limits): the helpers running
      // and the caller do the work.
    }
    helpers = std::min(helpers, static_cast<int>(threads_.size()));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &job;
      taking_ = helpers;
      running_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    job(0);
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, [&] { return running_ == 0; });
    job_ = nullptr;
    return true;
  }

  // After fork() the child has none of the parent's helper threads: it gets a pool of its own (the
  // old one is left as it is, never touched again).
  static HelperPool*& instance() {
    static HelperPool* pool = [] {
#ifdef GEOSHIFT_AT_FORK
      pthread_atfork(nullptr, nullptr, [] { instance() = new HelperPool(); });
#endif
      return new HelperPool();  // never destroyed: helpers may still wait on it at exit
    }();
    return pool;
  }

 private:
  void helperLoop(int index) {
    long seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (index > taking_) continue;
      const std::function<void(int)>* job = job_;
      lock.unlock();
      (*job)(index);
      lock.lock();
      if (--running_ == 0) finished_.notify_one();
    }
  }

  std::mutex inUse_;  // held by the call using the pool
  std::mutex mutex_;  // guards the fields below
  std::condition_variable wake_, finished_;
  std::vector<std::thread> threads_;
  const std::function<void(int)>* job_ = nullptr;
  int taking_ = 0;   // helpers 1 .. taking_ take part in the current job
  int running_ = 0;  // of those, the ones not finished
  long generation_ = 0;
};

// Set while this thread runs a pooled call's work: a parallelFor inside runs serially.
thread_local bool insidePooledCall = false;
#endif

}  // namespace

namespace detail {
void parallelForChunks(int count, const ParallelOptions& options, const Progress& progress,
                       std::string_view stage, double from, double to, ChunkRunner runner) {
  if (count <= 0) return;
  const int chunk = std::max(1, options.chunk);
  const int chunks = (count + chunk - 1) / chunk;

  // Chunk 0 is the caller's, whatever the helpers do meanwhile: the caller always runs a chunk and
  // reports after it, so a cancel raised from that report stops the call at the next chunk even
  // when the helpers (kept between calls, awake at once) could take every other chunk first.
  std::atomic<int> next{1};
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
    // The clock is read only when there is someone to report to (in the browser each read is a call
    // out to JS: 1% of a denoise, whose inner calls report nothing).
    const bool reports = caller && static_cast<bool>(progress.report);
    auto lastReport = reports ? Clock::now() : Clock::time_point{};
    const auto interval = std::chrono::duration<double>(options.reportSeconds);
    bool first = caller;
    try {
      for (;;) {
        if (stop.load(std::memory_order_relaxed)) return;
        if (progress.cancelled()) {
          if (caller) progress.step(from, stage);  // throws Cancelled
          stop.store(true);
          return;
        }
        const int c = first ? 0 : next.fetch_add(1, std::memory_order_relaxed);
        first = false;
        if (c >= chunks) return;
        const int begin = c * chunk, end = std::min(count, begin + chunk);
        runner.run(runner.context, begin, end, worker);
        const int finished = done.fetch_add(end - begin, std::memory_order_relaxed) + (end - begin);
        if (reports && Clock::now() - lastReport >= interval) {
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
  const int threads = insidePooledCall ? 1 : std::min(resolveThreads(options.threads), chunks);
  if (threads == 1) {
    work(0, true);
  } else {
    const std::function<void(int)> job = [&](int worker) {
      insidePooledCall = true;
      work(worker, worker == 0);
      insidePooledCall = false;
    };
    if (!HelperPool::instance()->run(threads - 1, job)) {
      // The pool is busy with another thread's call: threads of this call's own.
      std::vector<std::thread> own;
      own.reserve(threads - 1);
      try {
        for (int w = 1; w < threads; ++w) own.emplace_back(work, w, false);
      } catch (...) {
        // Could not start a thread: the ones running and the caller finish the work.
      }
      work(0, true);
      for (std::thread& t : own) t.join();
    }
  }
#endif
  if (failure) std::rethrow_exception(failure);
  if (progress.cancelled()) progress.step(from, stage);  // a worker saw it first
  progress.step(to, stage);
}

}  // namespace detail
}  // namespace geoshift

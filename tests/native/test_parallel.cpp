// parallelFor (parallel.hpp): every index once, whatever the threads; its helper threads are kept
// between calls, so what a call leaves behind (an exception, a nested call, a call from another
// thread at the same time) must not change the next one.
#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "geoshift/parallel.hpp"

#if defined(__unix__) || defined(__APPLE__)
#include <sys/wait.h>
#include <unistd.h>
#endif

using namespace geoshift;

namespace {

// Runs parallelFor over [0, n) with `threads`, counting each index's calls and recording the
// workers seen; the body may do more through `extra`.
template <class Extra>
std::vector<int> countCalls(int n, int threads, int chunk, Extra&& extra, std::vector<char>* workersSeen = nullptr) {
  std::vector<std::atomic<int>> calls(n);
  ParallelOptions o;
  o.threads = threads;
  o.chunk = chunk;
  parallelFor(n, o, Progress{}, "", 0, 1, [&](int i, int worker) {
    calls[i].fetch_add(1);
    if (workersSeen) (*workersSeen)[worker] = 1;
    extra(i, worker);
  });
  std::vector<int> out(n);
  for (int i = 0; i < n; ++i) out[i] = calls[i].load();
  return out;
}

}  // namespace

TEST_CASE("parallelFor calls every index exactly once, call after call", "[parallel]") {
  const int hardware = resolveThreads(0);
  for (int round = 0; round < 50; ++round) {
    const int threads = 1 + round % 4;  // asks for more helpers, then fewer, then more again
    const int n = 1 + 37 * round;
    std::vector<char> seen(std::max(threads, hardware), 0);
    const std::vector<int> calls = countCalls(n, threads, 1 + round % 5, [](int, int) {}, &seen);
    for (int i = 0; i < n; ++i) REQUIRE(calls[i] == 1);
    // Worker indices stay below the threads the call may use.
    for (int w = std::min(threads, hardware); w < static_cast<int>(seen.size()); ++w) REQUIRE(seen[w] == 0);
  }
}

TEST_CASE("parallelFor rethrows a body's exception and the next call still runs every index", "[parallel]") {
  ParallelOptions o;
  o.threads = 4;
  o.chunk = 1;
  REQUIRE_THROWS_WITH(parallelFor(1000, o, Progress{}, "", 0, 1,
                                  [](int i, int) {
                                    if (i == 517) throw std::runtime_error("index 517");
                                  }),
                      "index 517");
  const std::vector<int> calls = countCalls(1000, 4, 1, [](int, int) {});
  for (int i = 0; i < 1000; ++i) REQUIRE(calls[i] == 1);
}

TEST_CASE("a parallelFor inside a parallelFor's body runs every inner index once", "[parallel]") {
  const int outer = 64, inner = 50;
  std::vector<std::atomic<int>> innerCalls(outer * inner);
  const std::vector<int> calls = countCalls(outer, 4, 1, [&](int i, int) {
    ParallelOptions o;
    o.threads = 4;
    o.chunk = 1;
    std::vector<char> seen(resolveThreads(0), 0);
    parallelFor(inner, o, Progress{}, "", 0, 1, [&](int j, int worker) {
      innerCalls[i * inner + j].fetch_add(1);
      seen[worker] = 1;
    });
  });
  for (int i = 0; i < outer; ++i) REQUIRE(calls[i] == 1);
  for (int k = 0; k < outer * inner; ++k) REQUIRE(innerCalls[k].load() == 1);
}

TEST_CASE("parallelFor called from two threads at once runs both calls' indices once", "[parallel]") {
  const int n = 20000;
  std::vector<int> a, b;
  for (int round = 0; round < 10; ++round) {
    std::thread other([&] { b = countCalls(n, 3, 7, [](int, int) {}); });
    a = countCalls(n, 3, 5, [](int, int) {});
    other.join();
    for (int i = 0; i < n; ++i) {
      REQUIRE(a[i] == 1);
      REQUIRE(b[i] == 1);
    }
  }
}

#if defined(__unix__) || defined(__APPLE__)
TEST_CASE("after fork() the child's parallelFor runs every index (the parent's helpers are not there)", "[parallel]") {
  // The helpers exist in the parent before the fork.
  REQUIRE(countCalls(1000, 2, 1, [](int, int) {}) == std::vector<int>(1000, 1));
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    alarm(60);  // a child waiting for helpers it does not have would hang: end it instead
    const std::vector<int> calls = countCalls(5000, 2, 1, [](int, int) {});
    _exit(calls == std::vector<int>(5000, 1) ? 0 : 1);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
}
#endif

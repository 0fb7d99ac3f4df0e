// The CLI's operator new and delete (cli/allocation.cpp), linked into this test program: arrays of
// 1 MB and more of a recurring size are kept and handed out again, never beyond the high-water mark
// of the arrays in use, and never to two holders at once.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include <sys/resource.h>

#include "allocation.hpp"

using geoshift::cli::keptArrays;
using geoshift::cli::releaseKeptArrays;

namespace {

constexpr std::size_t kMB = std::size_t{1} << 20;

// An allocation the compiler may not elide (new and delete of an array nothing reads may be).
char* newArray(std::size_t size) {
  char* p = new char[size];
  asm volatile("" : : "r"(p) : "memory");
  return p;
}

// Page faults taken while an array is written through: near none for pages already resident.
long faultsWriting(char* p, std::size_t size, char value) {
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  std::memset(p, value, size);
  asm volatile("" : : "r"(p) : "memory");
  getrusage(RUSAGE_SELF, &after);
  return after.ru_minflt - before.ru_minflt;
}

// Whether this build keeps arrays; a warning where it does not.
bool keeps() {
  if (keptArrays().enabled) return true;
  WARN("this build keeps no arrays (AddressSanitizer, or no glibc): nothing to test");
  return false;
}

bool withinHighWater() {
  const auto k = keptArrays();
  return k.inUse + k.kept <= k.mostInUse;
}

}  // namespace

TEST_CASE("kept arrays: a size asked for twice is kept and handed out again", "[cli][allocation]") {
  if (!keeps()) return;
  releaseKeptArrays();
  const std::size_t size = 3 * kMB + 123;  // a size nothing else in this program asks for

  char* first = newArray(size);
  std::memset(first, 1, size);
  delete[] first;
  CHECK(keptArrays().kept == 0);  // asked for once: released

  char* second = newArray(size);
  std::memset(second, 2, size);
  delete[] second;
  CHECK(keptArrays().kept >= size);  // asked for twice: kept
  CHECK(withinHighWater());

  char* third = newArray(size);
  CHECK(static_cast<void*>(third) == static_cast<void*>(second));  // the kept array, with what it held
  CHECK(third[size - 1] == 2);
  CHECK(keptArrays().kept == 0);
  CHECK(faultsWriting(third, size, 3) < 16);  // its pages are resident: 768 without the reuse

  // Not for a request more than 1/16 larger: that one is fresh, and the kept array goes to make room.
  delete[] third;
  REQUIRE(keptArrays().kept >= size);
  char* larger = newArray(size + size / 8);
  CHECK(keptArrays().kept == 0);
  CHECK(withinHighWater());
  delete[] larger;
  releaseKeptArrays();
  CHECK(keptArrays().kept == 0);
}

TEST_CASE("kept arrays: a request no kept array holds takes the pages of several", "[cli][allocation]") {
  if (!keeps()) return;
  releaseKeptArrays();
  const std::size_t size = 2 * kMB + 12345;  // a size nothing else in this program asks for
  for (int round = 0; round < 2; ++round) {  // asked for four times: both kept
    char* a = newArray(size);
    char* b = newArray(size);
    std::memset(a, 1, size);
    std::memset(b, 2, size);
    delete[] a;
    delete[] b;
  }
  const auto before = keptArrays();
  REQUIRE(before.kept >= 2 * size);
  const std::size_t larger = size + size / 2;  // more than either holds, less than both
  char* joined = newArray(larger);
  const auto after = keptArrays();
  CHECK(after.kept + larger <= before.kept);  // taken from the kept arrays ...
  CHECK(after.inUse + after.kept <= after.mostInUse);
  CHECK(faultsWriting(joined, larger, 5) < 16);  // ... with their resident pages
  CHECK(std::all_of(joined, joined + larger, [](char c) { return c == 5; }));
  delete[] joined;
  releaseKeptArrays();
  CHECK(keptArrays().kept == 0);
}

TEST_CASE("kept arrays: never beyond the high-water mark, never held twice", "[cli][allocation]") {
  if (!keeps()) return;
  releaseKeptArrays();
  // Random allocations and frees of a few recurring sizes around 1 MB and up, each array filled with
  // its own tag and checked before it is freed: an array handed to two holders would be overwritten.
  const std::size_t sizes[] = {kMB, kMB + 4096, 2 * kMB + 100, 3 * kMB, 5 * kMB + 7, 512 * 1024};
  struct Held {
    std::unique_ptr<std::uint32_t[]> data;
    std::size_t words;
    std::uint32_t tag;
  };
  std::vector<Held> held;
  std::mt19937 random(7);
  std::uint32_t nextTag = 1;
  bool reused = false;
  std::vector<const void*> freed;
  for (int step = 0; step < 2000; ++step) {
    if (held.size() < 6 && (held.empty() || random() % 2 == 0)) {
      const std::size_t words = sizes[random() % 6] / 4;
      Held h{std::unique_ptr<std::uint32_t[]>(new std::uint32_t[words]), words, nextTag++};
      reused = reused || std::find(freed.begin(), freed.end(), h.data.get()) != freed.end();
      std::fill(h.data.get(), h.data.get() + words, h.tag);
      held.push_back(std::move(h));
    } else {
      const std::size_t i = random() % held.size();
      const Held& h = held[i];
      const bool intact = std::all_of(h.data.get(), h.data.get() + h.words, [&](std::uint32_t w) { return w == h.tag; });
      REQUIRE(intact);
      freed.push_back(h.data.get());
      held.erase(held.begin() + static_cast<std::ptrdiff_t>(i));
    }
    REQUIRE(withinHighWater());
  }
  CHECK(reused);  // the kept arrays were handed out again
  held.clear();
  releaseKeptArrays();
  CHECK(keptArrays().kept == 0);
}

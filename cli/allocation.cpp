// The CLI's operator new and delete (Linux with glibc; elsewhere the defaults): its arrays of 1 MB
// and more kept for reuse within their own high-water mark, the largest on transparent huge pages.
//
// A denoise allocates its per-pass arrays afresh (about 40 MB a pass on 144k vertices). Each array
// of 1 MB and more gets its own mapping (main.cpp), returned to the kernel when freed, whose 4 KB
// pages fault in one by one (and are cleared) when the next pass's array is first written: about a
// fifth of a 144k-vertex denoise on one thread. So a freed array of a size that was asked for twice
// (a pass's arrays recur, to the byte) is kept and handed to the next request it exceeds by at most
// 1/16, as long as the arrays of 1 MB and more in use and those kept together stay within the most
// that were ever in use at once: a freed array is released instead when keeping it would exceed
// that, and kept arrays are released, oldest first, before a fresh one would. A kept array stands
// in for one the next pass would have mapped, so the peak stays where it was; what is kept is
// released before a result is written (docs/denoising.md#speed-and-memory).
//
// Where the kernel hands out huge pages only on request (transparent_hugepage = madvise, as on
// Debian), the 2 MB-aligned interior of each fresh array of 8 MB and more is requested as huge pages
// before it is touched: 512 times fewer faults. Not for smaller ones: a vector grown by doubling
// leaves capacity it never writes, which huge pages would make resident (from 4 MB up, the OBJ scan
// peaked 4 MB higher; from 8 MB, not at all). glibc's own switch for this
// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1) is read from the environment only.
#include <cstdio>  // first: it defines __GLIBC__ where glibc is the C library
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>

#include "allocation.hpp"

#if defined(__GLIBC__) && defined(__linux__)
#include <malloc.h>
#include <sys/mman.h>

#ifdef MADV_HUGEPAGE
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kKept = std::size_t{1} << 20;  // arrays this large (glibc's usable size) may be kept
// Under AddressSanitizer every array is freed, so that a use after free is still caught.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kKeeps = false;
#elif defined(__has_feature)
constexpr bool kKeeps = !__has_feature(address_sanitizer);
#else
constexpr bool kKeeps = true;
#endif

// Under one lock, taken for arrays of 1 MB and more only. Sizes are glibc's usable sizes, so that a
// delete knows the size of what it frees.
std::mutex keptLock;  // constant-initialised: usable before any static constructor runs
// The arrays of 1 MB and more in use, the most there ever were at once, and the bytes kept.
std::size_t inUse = 0, mostInUse = 0, keptBytes = 0;
// The kept arrays, oldest first.
struct Block {
  void* p;
  std::size_t size;
};
constexpr int kSlots = 64;
Block kept[kSlots];
int keptCount = 0;
// The sizes requested, with how often: only an array of a size asked for twice before is kept (a
// pass's arrays recur, to the byte; a file's text, read once, does not). Sizes within two pages of
// each other count as one.
struct Asked {
  std::size_t size;
  int count;
};
Asked asked[kSlots];
int askedCount = 0;

// A kept array serves a request it exceeds by at most 1/16.
bool fits(std::size_t array, std::size_t request) { return array >= request && array - request <= request / 16; }
bool same(std::size_t a, std::size_t b) { return (a > b ? a - b : b - a) <= 8192; }

void* take(int i) {  // with keptLock held
  void* p = kept[i].p;
  keptBytes -= kept[i].size;
  for (int j = i + 1; j < keptCount; ++j) kept[j - 1] = kept[j];
  --keptCount;
  return p;
}

void count(std::size_t size) {  // with keptLock held
  for (int i = 0; i < askedCount; ++i)
    if (same(asked[i].size, size)) {
      ++asked[i].count;
      return;
    }
  if (askedCount == kSlots) {  // the oldest size goes
    for (int j = 1; j < askedCount; ++j) asked[j - 1] = asked[j];
    --askedCount;
  }
  asked[askedCount++] = {size, 1};
}

bool recurs(std::size_t size) {  // with keptLock held
  for (int i = 0; i < askedCount; ++i)
    if (same(asked[i].size, size)) return asked[i].count >= 2;
  return false;
}

void* allocate(std::size_t size) {
  if (size >= kKept) {
    const std::lock_guard<std::mutex> hold(keptLock);
    count(size);
    // The smallest kept array that fits.
    int best = -1;
    for (int i = 0; i < keptCount; ++i)
      if (fits(kept[i].size, size) && (best < 0 || kept[i].size < kept[best].size)) best = i;
    if (best >= 0) {
      inUse += kept[best].size;
      mostInUse = std::max(mostInUse, inUse);
      return take(best);
    }
    // A fresh array: the oldest kept ones go first where it would take the process past its high-water mark.
    while (keptCount > 0 && inUse + keptBytes + size > mostInUse) std::free(take(0));
  }
  void* p = std::malloc(size == 0 ? 1 : size);
  if (!p) throw std::bad_alloc();
  if (size >= 4 * kHugePage) {  // 8 MB
    const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(p) + size) & ~(kHugePage - 1);
    // Advice only: where it is refused, the pages are ordinary ones.
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
  if (const std::size_t s = malloc_usable_size(p); s >= kKept) {
    const std::lock_guard<std::mutex> hold(keptLock);
    inUse += s;
    mostInUse = std::max(mostInUse, inUse);
  }
  return p;
}

void deallocate(void* p) noexcept {
  if (!p) return;
  const std::size_t s = malloc_usable_size(p);
  if (s >= kKept) {
    const std::lock_guard<std::mutex> hold(keptLock);
    inUse -= s;
    if (kKeeps && inUse + keptBytes + s <= mostInUse && recurs(s)) {
      if (keptCount == kSlots) std::free(take(0));
      kept[keptCount++] = {p, s};
      keptBytes += s;
      return;
    }
  }
  std::free(p);
}

}  // namespace

#define GEOSHIFT_KEPT_ARRAYS
namespace geoshift::cli {
void releaseKeptArrays() {
  const std::lock_guard<std::mutex> hold(keptLock);
  while (keptCount > 0) std::free(take(0));
}
KeptArrays keptArrays() {
  const std::lock_guard<std::mutex> hold(keptLock);
  return {kKeeps, keptBytes, inUse, mostInUse};
}
}  // namespace geoshift::cli

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete(void* p) noexcept { deallocate(p); }
void operator delete[](void* p) noexcept { deallocate(p); }
void operator delete(void* p, std::size_t) noexcept { deallocate(p); }
void operator delete[](void* p, std::size_t) noexcept { deallocate(p); }
#endif
#endif

#ifndef GEOSHIFT_KEPT_ARRAYS
namespace geoshift::cli {
void releaseKeptArrays() {}  // nothing is kept with the default operator new
KeptArrays keptArrays() { return {}; }
}  // namespace geoshift::cli
#endif

// The CLI's operator new and delete (Linux with glibc; elsewhere the defaults): its arrays of 1 MB
// and more on mappings of their own, kept for reuse within their own high-water mark, the largest
// on transparent huge pages.
//
// A denoise allocates its per-pass arrays afresh (about 40 MB a pass on 144k vertices). On a
// mapping of its own (as glibc gives arrays of 1 MB and more, main.cpp), an array's pages are
// returned to the kernel when it is freed, and fault in one by one (and are cleared) when the next
// pass's array is first written: about a fifth of a 144k-vertex denoise on one thread, more on a
// virtual machine. So each array of 1 MB and more gets a mapping of its own here, with a header, and
// a freed one whose size was asked for twice (a pass's arrays recur, to the byte; a file's text,
// read once, does not) is kept. The next request that fits in a kept mapping takes its first pages
// and leaves the rest kept (a mapping can be cut at any page), so a freed array of 24 bytes a face
// serves the next pass's two of 24 bytes a vertex. One bound holds throughout: the mappings in use
// and those kept together stay within the most that were ever in use at once. A freed mapping is
// returned instead when keeping it would break it, and kept ones, oldest first, before a fresh one
// would. A kept mapping stands in for one that would have been mapped anyway, so the peak stays
// where it was; what is kept is returned before a result is written
// (docs/denoising.md#speed-and-memory). Under AddressSanitizer every array goes to malloc, so that
// a use after free is still caught.
//
// Where the kernel hands out huge pages only on request (transparent_hugepage = madvise, as on
// Debian), the 2 MB-aligned interior of each fresh mapping of 8 MB and more is requested as huge
// pages before it is touched: 512 times fewer faults. Not for smaller ones: a vector grown by
// doubling leaves capacity it never writes, which huge pages would make resident (from 4 MB up, the
// OBJ scan peaked 4 MB higher; from 8 MB, not at all).
#include <cstdio>  // first: it defines __GLIBC__ where glibc is the C library
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>

#include "allocation.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define GEOSHIFT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GEOSHIFT_ASAN 1
#endif
#endif

#if defined(__GLIBC__) && defined(__linux__) && !defined(GEOSHIFT_ASAN)
#include <sys/mman.h>

#ifdef MADV_HUGEPAGE
#define GEOSHIFT_KEPT_ARRAYS
namespace {

constexpr std::size_t kPage = 4096;
constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kLarge = std::size_t{1} << 20;  // requests this large get mappings of their own
// A mapping starts with its header; the array follows, 64-byte aligned. A pointer is one of these
// arrays when it lies 64 bytes into a page (so the header's page is the pointer's own, safe to read
// whatever the pointer) and the header's tag is the pointer's address in disguise.
constexpr std::size_t kHeader = 64;
constexpr std::uint64_t kMagic = 0x67656f7368696674;  // "geoshift"
struct Header {
  std::uint64_t tag;
  std::size_t bytes;  // of the mapping, header included: whole pages
};

std::size_t mappingFor(std::size_t request) { return (request + kHeader + kPage - 1) & ~(kPage - 1); }

bool isMapping(void* p) {
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  return a % kPage == kHeader && reinterpret_cast<const Header*>(a - kHeader)->tag == (kMagic ^ a);
}

// Under one lock, taken for arrays of 1 MB and more only: the bytes of the mappings in use, the most
// there ever were at once, the bytes kept, and the kept mappings, oldest first.
std::mutex keptLock;  // constant-initialised: usable before any static constructor runs
std::size_t inUse = 0, mostInUse = 0, keptBytes = 0;
struct Range {
  char* p;
  std::size_t bytes;
};
constexpr int kSlots = 64;
Range kept[kSlots];
int keptCount = 0;
// The mapping sizes asked for, with how often (within two pages of each other counted as one):
// only a mapping of a size asked for twice is kept when freed.
struct Asked {
  std::size_t bytes;
  int count;
};
Asked asked[kSlots];
int askedCount = 0;

bool same(std::size_t a, std::size_t b) { return (a > b ? a - b : b - a) <= 2 * kPage; }

void count(std::size_t bytes) {  // with keptLock held
  for (int i = 0; i < askedCount; ++i)
    if (same(asked[i].bytes, bytes)) {
      ++asked[i].count;
      return;
    }
  if (askedCount == kSlots) {  // the oldest size goes
    for (int j = 1; j < askedCount; ++j) asked[j - 1] = asked[j];
    --askedCount;
  }
  asked[askedCount++] = {bytes, 1};
}

bool recurs(std::size_t bytes) {  // with keptLock held
  for (int i = 0; i < askedCount; ++i)
    if (same(asked[i].bytes, bytes)) return asked[i].count >= 2;
  return false;
}

Range take(int i) {  // with keptLock held
  const Range r = kept[i];
  keptBytes -= r.bytes;
  for (int j = i + 1; j < keptCount; ++j) kept[j - 1] = kept[j];
  --keptCount;
  return r;
}

void release(Range r) { munmap(r.p, r.bytes); }

void keep(Range r) {  // with keptLock held
  if (keptCount == kSlots) release(take(0));
  kept[keptCount++] = r;
  keptBytes += r.bytes;
}

// What is left of kept mapping r once its first `used` bytes are taken: kept if it can hold a large
// array itself (a mapping is cut at a page boundary like any other), else returned.
void keepRest(Range r, std::size_t used) {  // with keptLock held
  if (r.bytes == used) return;
  const Range rest{r.p + used, r.bytes - used};
  if (rest.bytes >= mappingFor(kLarge))
    keep(rest);
  else
    release(rest);
}

// Room for `bytes` more in use within the high-water mark: kept mappings go, oldest first.
void makeRoom(std::size_t bytes) {  // with keptLock held
  while (keptCount > 0 && inUse + keptBytes + bytes > mostInUse) release(take(0));
}

void nowInUse(std::size_t bytes) {  // with keptLock held
  inUse += bytes;
  mostInUse = std::max(mostInUse, inUse);
}

void* place(char* mapping, std::size_t bytes) {
  char* p = mapping + kHeader;
  *reinterpret_cast<Header*>(mapping) = {kMagic ^ reinterpret_cast<std::uintptr_t>(p), bytes};
  return p;
}

void* allocateLarge(std::size_t size) {
  const std::size_t bytes = mappingFor(size);
  {
    const std::lock_guard<std::mutex> hold(keptLock);
    count(bytes);
    // The smallest kept mapping that holds it: its first pages.
    int best = -1;
    for (int i = 0; i < keptCount; ++i)
      if (kept[i].bytes >= bytes && (best < 0 || kept[i].bytes < kept[best].bytes)) best = i;
    if (best >= 0) {
      const Range r = take(best);
      keepRest(r, bytes);
      nowInUse(bytes);
      return place(r.p, bytes);
    }
    // No kept mapping holds it, but together they do: their pages are moved into one fresh range
    // (mremap moves page tables, not bytes), largest first, so that nothing new becomes resident.
    if (keptBytes >= bytes) {
      void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (m != MAP_FAILED) {
        char* to = static_cast<char*>(m);
        std::size_t filled = 0;
        while (filled < bytes && keptCount > 0) {
          int largest = 0;
          for (int i = 1; i < keptCount; ++i)
            if (kept[i].bytes > kept[largest].bytes) largest = i;
          const Range r = take(largest);
          const std::size_t n = std::min(r.bytes, bytes - filled);
          if (mremap(r.p, n, n, MREMAP_MAYMOVE | MREMAP_FIXED, to + filled) == MAP_FAILED) {
            keep(r);  // not movable (it spans two of the kernel's areas): the rest of the range is fresh
            break;
          }
          keepRest(r, n);
          filled += n;
        }
        makeRoom(bytes);  // what was not filled is fresh, as a fresh mapping is
        nowInUse(bytes);
        return place(to, bytes);
      }
    }
    // A fresh mapping, within the high-water mark.
    makeRoom(bytes);
    nowInUse(bytes);
  }
  void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) {
    const std::lock_guard<std::mutex> hold(keptLock);
    inUse -= bytes;
    throw std::bad_alloc();
  }
  if (bytes >= 4 * kHugePage) {  // 8 MB
    const auto begin = (reinterpret_cast<std::uintptr_t>(m) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(m) + bytes) & ~(kHugePage - 1);
    // Advice only: where it is refused, the pages are ordinary ones.
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
  return place(static_cast<char*>(m), bytes);
}

void* allocate(std::size_t size) {
  if (size >= kLarge) return allocateLarge(size);
  void* p = std::malloc(size == 0 ? 1 : size);
  if (!p) throw std::bad_alloc();
  return p;
}

void deallocate(void* p) noexcept {
  if (!p) return;
  if (!isMapping(p)) return std::free(p);
  char* mapping = static_cast<char*>(p) - kHeader;
  const std::size_t bytes = reinterpret_cast<const Header*>(mapping)->bytes;
  reinterpret_cast<Header*>(mapping)->tag = 0;  // no longer an array
  const std::lock_guard<std::mutex> hold(keptLock);
  inUse -= bytes;
  if (inUse + keptBytes + bytes <= mostInUse && recurs(bytes))
    keep({mapping, bytes});
  else
    release({mapping, bytes});
}

}  // namespace

namespace geoshift::cli {
void releaseKeptArrays() {
  const std::lock_guard<std::mutex> hold(keptLock);
  while (keptCount > 0) release(take(0));
}
KeptArrays keptArrays() {
  const std::lock_guard<std::mutex> hold(keptLock);
  return {true, keptBytes, inUse, mostInUse};
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

// The CLI's largest arrays on transparent huge pages (Linux with glibc; elsewhere the default
// operator new). A denoise allocates its per-pass arrays afresh (about 40 MB a pass on 144k
// vertices); each array of 1 MB and more gets its own mapping (main.cpp) whose 4 KB pages fault in
// one by one as they are first written, which cost a tenth of the 144k-vertex denoise. Where the
// kernel hands out huge pages only on request (transparent_hugepage = madvise, as on Debian), the
// 2 MB-aligned interior of each array of 8 MB and more is requested as huge pages before it is
// touched: 512 times fewer faults for the largest per-pass arrays. Not for smaller ones: a vector
// grown by doubling leaves capacity it never writes, which huge pages would make resident (from
// 4 MB up, the OBJ scan peaked 4 MB higher; from 8 MB, not at all; docs/denoising.md#speed-and-memory).
// glibc's own switch for this (GLIBC_TUNABLES=glibc.malloc.hugetlb=1) is read from the environment only.
#include <cstdio>  // first: it defines __GLIBC__ where glibc is the C library
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__GLIBC__) && defined(__linux__)
#include <sys/mman.h>

#ifdef MADV_HUGEPAGE
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

void* allocate(std::size_t size) {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (!p) throw std::bad_alloc();
  if (size >= 4 * kHugePage) {  // 8 MB
    const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(p) + size) & ~(kHugePage - 1);
    // Advice only: where it is refused, the pages are ordinary ones.
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
  return p;
}

}  // namespace

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
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#endif
#endif

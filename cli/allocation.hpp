// The CLI's operator new and delete (allocation.cpp): the arrays of 1 MB and more it keeps for reuse.
#pragma once

#include <cstddef>

namespace geoshift::cli {

// The arrays of 1 MB and more that the CLI keeps for reuse (allocation.cpp): whether it keeps any
// (not under AddressSanitizer, nor without glibc), the bytes kept, those in use and the most ever in
// use at once (bytes of their mappings, headers included).
struct KeptArrays {
  bool enabled = false;
  std::size_t kept = 0, inUse = 0, mostInUse = 0;
};
KeptArrays keptArrays();
// Hands the kept arrays back to the system (save() does, so that none is held while a result is
// written).
void releaseKeptArrays();

}  // namespace geoshift::cli

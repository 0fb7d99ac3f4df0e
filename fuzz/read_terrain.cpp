// libFuzzer harness for a terrain reader (LAS or GeoTIFF, by GEOSHIFT_FUZZ_EXTENSION): the bytes
// become a file read through readTerrain as the CLI's `terrain` command reads it, so the point set
// is triangulated (Delaunay) and the raster gridded. A clean InputError is the expected outcome for
// most inputs; anything the sanitizers or libFuzzer catch is a defect.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "geoshift/error.hpp"
#include "geoshift/terrain.hpp"

#ifndef GEOSHIFT_FUZZ_EXTENSION
#error "define GEOSHIFT_FUZZ_EXTENSION, e.g. \".las\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path dir = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    return (dir / ("geoshift-fuzz-terrain-" + std::to_string(::getpid()) + GEOSHIFT_FUZZ_EXTENSION)).string();
  }();
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    geoshift::readTerrain(path);
  } catch (const geoshift::InputError&) {
  }
  return 0;
}

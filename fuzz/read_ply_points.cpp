// libFuzzer harness for the terrain reader of PLY point sets (readPlyPoints), which shares the PLY
// container parser with the mesh reader but reads classes and colors its own way.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "geoshift/error.hpp"
#include "geoshift/terrain.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path dir = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    return (dir / ("geoshift-fuzz-points-" + std::to_string(::getpid()) + ".ply")).string();
  }();
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    geoshift::readPlyPoints(path);
  } catch (const geoshift::InputError&) {
  }
  return 0;
}

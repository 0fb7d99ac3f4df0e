// libFuzzer harness for one mesh reader: the input bytes become a file with the reader's extension
// (GEOSHIFT_FUZZ_EXTENSION), read through readDocument as the CLI reads it; every part is built into
// a welded mesh (mesh building and repair on whatever soup the reader let through), so is the
// world-space soup of all instances, and the document is written back and read again.
// A clean InputError is the expected outcome for most inputs; anything else the sanitizers or
// libFuzzer catch (crash, leak, undefined behaviour, timeout, out of memory) is a defect.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "geoshift/error.hpp"
#include "geoshift/io.hpp"
#include "geoshift/mesh.hpp"

#ifndef GEOSHIFT_FUZZ_EXTENSION
#error "define GEOSHIFT_FUZZ_EXTENSION, e.g. \".ply\""
#endif

namespace {

std::string inputPath() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path dir = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
  return (dir / ("geoshift-fuzz-" + std::to_string(::getpid()) + GEOSHIFT_FUZZ_EXTENSION)).string();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = inputPath();
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  geoshift::ReadOptions options;
  options.maxVertices = 1 << 16;  // keeps each execution short; the limit itself is under test
  geoshift::Document doc;
  try {
    doc = geoshift::readDocument(path, options);
  } catch (const geoshift::InputError&) {
    return 0;
  }
  for (const geoshift::MeshPart& part : doc.parts) {
    try {
      geoshift::buildMesh(geoshift::partSoup(part));
    } catch (const geoshift::InputError&) {
    }
  }
  // All instances in world space (bounded by maxVertices at reading), as the writers of OFF, PLY and
  // STL and the CLI's compare see them.
  try {
    geoshift::buildMesh(geoshift::worldSoup(doc));
  } catch (const geoshift::InputError&) {
  }
  // Written back in its own format (what the CLI does after filtering) and read again.
  static const std::string written = path.substr(0, path.size() - std::strlen(GEOSHIFT_FUZZ_EXTENSION)) +
                                     "-written" + GEOSHIFT_FUZZ_EXTENSION;
  try {
    geoshift::writeDocument(doc, written);
    geoshift::readDocument(written, options);
  } catch (const geoshift::InputError&) {
  }
  return 0;
}

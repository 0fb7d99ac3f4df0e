#pragma once
// Helpers shared by the native tests.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "geoshift/error.hpp"

namespace geoshift::test {

// A file under ../shared/data (GEOSHIFT_SHARED_DATA in the environment overrides the build-time
// path), or nullopt when it is absent: tests that need it skip with a message.
inline std::optional<std::filesystem::path> sharedData(const std::string& relative) {
  const char* env = std::getenv("GEOSHIFT_SHARED_DATA");
  std::filesystem::path root = env && *env ? env : GEOSHIFT_SHARED_DATA;
  std::filesystem::path p = root / relative;
  if (std::filesystem::exists(p)) return p;
  return std::nullopt;
}

// Files shipped with the tests (tests/native/data).
inline std::filesystem::path testData(const std::string& relative) {
  return std::filesystem::path(GEOSHIFT_TEST_DATA) / relative;
}

// A fresh empty directory under the system temp dir, for outputs of one test.
inline std::filesystem::path tempDir(const std::string& name) {
  auto p = std::filesystem::temp_directory_path() / ("geoshift-test-" + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void spit(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

inline bool anyContains(const std::vector<std::string>& v, const std::string& s) {
  for (const auto& x : v)
    if (x.find(s) != std::string::npos) return true;
  return false;
}

// The message of the InputError that f throws, or "(no error)".
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace geoshift::test

// Skips the current test with a message (Catch2 v2 has no SKIP): prints why and returns.
#define GEOSHIFT_SKIP_IF_MISSING(opt, what)                                        \
  if (!(opt)) {                                                                    \
    WARN("skipped: " << (what) << " not found (../shared/data absent)");           \
    return;                                                                        \
  }

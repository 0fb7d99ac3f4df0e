#pragma once
// Running the geoshift executable from the tests as a user runs it (GEOSHIFT_CLI is its path).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "geoshift/mesh.hpp"
#include "support.hpp"

namespace geoshift::test {

namespace fs = std::filesystem;

struct Run {
  int code = -1;
  std::string out, err;
};

inline Run geoshiftCli(const std::string& args) {
  static int counter = 0;
  // Per process: ctest runs several test executables at once.
  const fs::path dir = fs::temp_directory_path() / ("geoshift-cli-io-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / ("out" + std::to_string(counter) + ".txt");
  const fs::path err = dir / ("err" + std::to_string(counter++) + ".txt");
  const std::string cmd = std::string("\"") + GEOSHIFT_CLI + "\" " + args + " >\"" + out.string() + "\" 2>\"" +
                          err.string() + "\" </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

inline void writeOff(const fs::path& path, const TriangleSoup& s) {
  std::ofstream o(path);
  o.precision(17);
  o << "OFF\n" << s.positions.size() << " " << s.faces.size() << " 0\n";
  for (const Vec3& p : s.positions) o << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const Face& f : s.faces) o << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
}

inline std::string q(const fs::path& p) { return "\"" + p.string() + "\""; }

}  // namespace geoshift::test

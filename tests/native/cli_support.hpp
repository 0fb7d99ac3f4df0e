#pragma once
// Running the geoshift executable from the tests as a user runs it (GEOSHIFT_CLI is its path).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

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

// The directory the CLI's captured output goes to: one per process (ctest runs several test
// executables at once), removed when the process ends so that runs leave nothing in the temp dir.
inline const fs::path& cliCaptureDir() {
  struct Dir {
    fs::path path = fs::temp_directory_path() / ("geoshift-cli-io-" + std::to_string(getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Dir dir;
  return dir.path;
}

inline Run geoshiftCli(const std::string& args) {
  static int counter = 0;
  const fs::path& dir = cliCaptureDir();
  const fs::path out = dir / ("out" + std::to_string(counter) + ".txt");
  const fs::path err = dir / ("err" + std::to_string(counter++) + ".txt");
  const std::string cmd = std::string("\"") + GEOSHIFT_CLI + "\" " + args + " >\"" + out.string() + "\" 2>\"" +
                          err.string() + "\" </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
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

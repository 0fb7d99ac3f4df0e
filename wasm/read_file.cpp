// readFile: the core's own readers (readDocument, core/src/io) on the bytes of a file the page was
// given, so that the app refuses a damaged file with the words the CLI uses (docs/io.md).
//
// The readers take a path (tinyobjloader and tinygltf open files themselves), so the bytes are
// written to Emscripten's in-memory file system under the file's own name, in a directory that is
// the current one: the core's messages then begin with the bare name, as the CLI's do when it is
// run beside the file. The copy is removed before returning, whatever happened.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "adapters.hpp"
#include "convert.hpp"
#include "geoshift/error.hpp"
#include "geoshift/io.hpp"
#include "geoshift/mesh.hpp"

namespace geoshift::wasm {

using emscripten::val;
namespace fs = std::filesystem;

namespace {

constexpr const char* kReadDirectory = "/geoshift-read";

// A browser's File.name has no directory part, but a caller of the module may pass anything.
std::string bareName(const std::string& name) {
  const std::size_t slash = name.find_last_of('/');
  std::string bare = slash == std::string::npos ? name : name.substr(slash + 1);
  if (bare.empty() || bare == "." || bare == "..") bare = "unnamed";
  return bare;
}

// Removes the in-memory copy when the read ends, also by an exception.
struct TemporaryFile {
  std::string name;
  ~TemporaryFile() {
    std::error_code ec;
    fs::remove(name, ec);
  }
};

// The part's arrays in the file's own vertex order, for callers that filter what they read (the npm
// package's read()): positions, indices, and normals, RGBA colors, extra attributes and the
// instances' world transforms (column-major 4x4) where the file has them.
void setArrays(val& p, const MeshPart& part) {
  std::vector<float> positions(3 * part.positions.size());
  for (std::size_t i = 0; i < part.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) positions[3 * i + c] = static_cast<float>(part.positions[i][c]);
  p.set("positions", copyOut("Float32Array", positions));
  std::vector<std::uint32_t> indices(3 * part.faces.size());
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    for (int c = 0; c < 3; ++c) indices[3 * f + c] = static_cast<std::uint32_t>(part.faces[f][c]);
  p.set("indices", copyOut("Uint32Array", indices));
  if (!part.normals.empty()) {
    std::vector<float> normals(3 * part.normals.size());
    for (std::size_t i = 0; i < part.normals.size(); ++i)
      for (int c = 0; c < 3; ++c) normals[3 * i + c] = static_cast<float>(part.normals[i][c]);
    p.set("normals", copyOut("Float32Array", normals));
  }
  if (!part.colors.empty()) {
    std::vector<float> colors(4 * part.colors.size());
    for (std::size_t i = 0; i < part.colors.size(); ++i)
      for (int c = 0; c < 4; ++c) colors[4 * i + c] = static_cast<float>(part.colors[i][c]);
    p.set("colors", copyOut("Float32Array", colors));
  }
  val attributes = val::object();
  for (const ExtraAttribute& extra : part.extras) attributes.set(extra.name, floatsOut(extra.values));
  p.set("attributes", attributes);
  std::vector<double> transforms;
  for (const Eigen::Matrix4d& m : part.instances) transforms.insert(transforms.end(), m.data(), m.data() + 16);
  p.set("transforms", copyOut("Float64Array", transforms));
}

val readFileChecked(const std::string& name, const val& bytes, double maxVertices, bool withArrays) {
  if (!isA(bytes, "Uint8Array")) throw InputError("the file's bytes must be a Uint8Array");
  if (!(maxVertices >= 1)) throw InputError("maxVertices must be at least 1");
  const std::vector<unsigned char> data = emscripten::convertJSArrayToNumberVector<unsigned char>(bytes);

  std::error_code ec;
  fs::create_directories(kReadDirectory, ec);
  fs::current_path(kReadDirectory, ec);
  if (ec) throw std::runtime_error("cannot use the in-memory file system: " + ec.message());
  TemporaryFile file{bareName(name)};
  {
    std::ofstream out(file.name, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
    out.close();
    if (!out) throw std::bad_alloc();  // MEMFS fails a write only when JS cannot grow its array
  }

  ReadOptions options;
  options.maxVertices = maxVertices >= 9.0e15 ? static_cast<std::size_t>(-1) : static_cast<std::size_t>(maxVertices);
  const Document doc = readDocument(file.name, options);

  val result = val::object();
  result.set("ok", true);
  val parts = val::array();
  double vertices = 0;
  double triangles = 0;
  for (const MeshPart& part : doc.parts) {
    // What every filter builds first (the CLI's commands too): a file whose triangles are all
    // degenerate is refused here rather than at the first run.
    const BuildReport report = [&] {
      try {
        return buildMesh(partSoup(part)).report;
      } catch (const InputError& e) {
        throw InputError(file.name + ": " + part.label + ": " + e.what());
      }
    }();
    val p = val::object();
    p.set("label", part.label);
    p.set("vertices", static_cast<double>(part.positions.size()));
    p.set("triangles", static_cast<double>(part.faces.size()));
    p.set("instances", static_cast<double>(part.instances.size()));
    p.set("report", reportToJs(report));
    if (withArrays) setArrays(p, part);
    parts.call<void>("push", p);
    vertices += static_cast<double>(part.positions.size());
    triangles += static_cast<double>(part.faces.size());
  }
  result.set("parts", parts);
  result.set("vertices", vertices);
  result.set("triangles", triangles);
  val warnings = val::array();
  for (const std::string& w : doc.warnings) warnings.call<void>("push", w);
  result.set("warnings", warnings);
  return result;
}

val readFileResult(const std::string& name, const val& bytes, double maxVertices, bool withArrays) {
  val result = guarded([&] { return readFileChecked(name, bytes, maxVertices, withArrays); });
  // The heap's limit may be the page's budget rather than wasm32's 4 GB (package/src/host.ts).
  if (result["outOfMemory"].isTrue())
    result.set("error", bareName(name) + ": out of memory: reading it needs more memory than the WebAssembly heap may grow to");
  return result;
}

}  // namespace

val readFile(const std::string& name, const val& bytes, double maxVertices) {
  return readFileResult(name, bytes, maxVertices, false);
}

val readFileWithArrays(const std::string& name, const val& bytes, double maxVertices, bool withArrays) {
  return readFileResult(name, bytes, maxVertices == 0 ? static_cast<double>(ReadOptions{}.maxVertices) : maxVertices, withArrays);
}

val readFileWithDefaultLimit(const std::string& name, const val& bytes) {
  return readFile(name, bytes, static_cast<double>(ReadOptions{}.maxVertices));
}

}  // namespace geoshift::wasm

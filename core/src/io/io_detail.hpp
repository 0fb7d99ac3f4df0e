#pragma once
// Private to the io layer: what each reader keeps of the parsed file so that writeDocument can put
// the new geometry back into it, and the helpers the format files share.
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/io.hpp"

namespace geoshift {

// One MeshPart of a glTF model: the triangle primitives that share its POSITION accessor.
struct GltfPartBinding {
  int mesh = -1;
  std::vector<int> primitives;
  int positionAccessor = -1;
  size_t vertexCount = 0;
};

struct GltfSource {
  tinygltf::Model model;
  std::string baseDir;  // for external images referenced by relative URI
  std::vector<GltfPartBinding> parts;
};

// OBJ is rewritten textually: writeObjInto scans the text again with the reader's scanner and
// replaces only the `v` lines whose values changed (read again from the line to tell), the `vn`
// lines and, when the normals are dropped, the `f` lines; everything else stays byte for byte. No
// line ranges are kept (they held up to 12.6 MB on a 144k-vertex scan). The text itself is kept
// unless ReadOptions::keepSourceText is false: then only the file's size and hash are, and the
// writer reads the file again and checks them (docs/io.md, OBJ).
struct ObjSource {
  std::string path;                // the file read, to read it again
  bool textKept = true;
  std::string text;                // the file's bytes, when kept
  std::uint64_t size = 0, hash = 0;  // of the bytes as read (FNV-1a), checked when the text was not kept
  size_t vertexCount = 0;          // `v` lines
  size_t normalLineCount = 0;      // `vn` lines
  // The vn line of each vertex (when every vertex has exactly one and the vn lines are
  // tinyobjloader's normals one for one), to write the result's normals back in place.
  std::vector<int> normalOf;
  std::vector<Vec3> normals;  // as exposed on read, to notice when a caller changed them
};

struct DocumentSource {
  FileFormat format = FileFormat::Obj;
  GltfSource gltf;  // Gltf, Glb
  ObjSource obj;    // Obj
};

namespace io {

// "PATH: what" — every message names the file first.
[[noreturn]] void fail(const std::string& path, const std::string& what);

bool isGltfFamily(FileFormat f);

// The writers' numbers: the shortest text that reads back as exactly the same double, as in
// messages (check.hpp).
using geoshift::formatNumber;

// std::from_chars for a double (the whole of [first, last), no leading space or '+'); false when
// it is not a number or out of range. Emscripten 3.1.6's libc++ has no floating-point from_chars
// or to_chars, so the wasm build (the web app's readers) goes through strtod / snprintf instead.
bool parseDouble(const char* first, const char* last, double& value);

// Files written together: each goes to a temporary file beside its target, and only when all of
// them are complete are they renamed into place. On any failure every temporary is removed.
class AtomicFileSet {
 public:
  void add(const std::string& path, std::string bytes);
  void commit();

 private:
  std::vector<std::pair<std::string, std::string>> files_;
};

// InputError when the part arrays do not match its positions (normals, colors, extras).
void checkPartSizes(const std::string& path, const MeshPart& part, size_t partIndex);

Document readGltf(const std::string& path, FileFormat format, const ReadOptions& options);
Document readObj(const std::string& path, const ReadOptions& options);
Document readOff(const std::string& path, const ReadOptions& options);
Document readPly(const std::string& path, const ReadOptions& options);
Document readStl(const std::string& path, const ReadOptions& options);

// Write back into the model that was read (everything that is not geometry kept).
std::vector<std::string> writeGltfInto(const Document& document, const std::string& path,
                                       FileFormat format);
// A minimal model built from the parts alone (source of another format).
std::vector<std::string> writeGltfFresh(const Document& document, const std::string& path,
                                        FileFormat format);
// Serialise a model (glTF JSON or GLB) together with its external buffers and copied images.
// Returns warnings (an external image that could not be copied).
std::vector<std::string> serializeGltf(tinygltf::Model model, const std::string& sourceBaseDir,
                                       const std::string& path, FileFormat format,
                                       AtomicFileSet& files);

std::vector<std::string> writeObjInto(const Document& document, const std::string& path);
std::vector<std::string> writeObjFresh(const Document& document, const std::string& path);
std::vector<std::string> writeOff(const Document& document, const std::string& path);
std::vector<std::string> writePly(const Document& document, const std::string& path);
std::vector<std::string> writeStl(const Document& document, const std::string& path);

std::string readWholeFile(const std::string& path);

// Normals are read as every writer must write them, unit length (glTF requires it; a viewer
// shades with them as given): one whose length is off by more than kUnitTolerance is normalized,
// a zero or non-finite one replaced by the area-weighted normal of the part's faces at its vertex
// (+z where no face uses it), each kind counted in a warning. Unit ones keep their exact values,
// so a file read and written back stays the same (docs/io.md#normals).
inline constexpr double kUnitTolerance = 1e-5;
void unitNormals(const std::string& path, MeshPart& part, std::vector<std::string>& warnings);

// --- glTF accessors (gltf_accessor.cpp) ---
// Where an accessor's elements sit: element i starts at data + offset + i * stride.
struct AccessorLayout {
  int buffer = -1;
  size_t offset = 0;
  size_t stride = 0;
  int components = 0;
  int componentSize = 0;
};
// Throws naming `where` when the accessor does not fit its buffer view or buffer.
AccessorLayout accessorLayout(const tinygltf::Model& model, int accessor, const std::string& path,
                              const std::string& where);
// All elements as doubles (count * components), sparse substitution applied; integer components
// are scaled to [0,1] / [-1,1] when the accessor is normalized or `normalize` is set. An accessor
// without a buffer view (all zeros) may declare at most maxWithoutData elements.
std::vector<double> readAccessor(const tinygltf::Model& model, int accessor, const std::string& path,
                                 const std::string& where, bool normalize = false,
                                 size_t maxWithoutData = static_cast<size_t>(-1));
// Stores one component of the given type; normalized integer types take values in [0,1] / [-1,1].
void storeComponent(unsigned char* dst, int componentType, bool normalized, double value);
int componentCount(int type);
// Recomputes an accessor's min/max from the values stored in its buffer (as stored: integer units
// for integer types, float-rounded for floats), as the spec requires for POSITION.
void updateMinMax(tinygltf::Model& model, int accessor);

}  // namespace io
}  // namespace geoshift

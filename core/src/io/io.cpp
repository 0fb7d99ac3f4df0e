// Format dispatch, atomic writes and the world-space soups.
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "io_detail.hpp"

namespace geoshift {
namespace fs = std::filesystem;

namespace io {

void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": " + what);
}

bool isGltfFamily(FileFormat f) { return f == FileFormat::Gltf || f == FileFormat::Glb; }

#ifndef __EMSCRIPTEN__
bool parseDouble(const char* first, const char* last, double& value) {
  const auto r = std::from_chars(first, last, value);
  return r.ec == std::errc() && r.ptr == last;
}
#else
bool parseDouble(const char* first, const char* last, double& value) {
  // from_chars' grammar: no leading space or '+', no hexadecimal prefix.
  if (first == last || *first == '+' || std::isspace(static_cast<unsigned char>(*first))) return false;
  const std::string text(first, last);
  if (text.find_first_of("xX") != std::string::npos) return false;
  errno = 0;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE;
}
#endif

void unitNormals(const std::string& path, MeshPart& part, std::vector<std::string>& warnings) {
  size_t rescaled = 0, replaced = 0;
  std::vector<Vec3> surface;  // area-weighted face normals summed per vertex, made when needed
  for (size_t v = 0; v < part.normals.size(); ++v) {
    Vec3& n = part.normals[v];
    const double length = n.norm();
    if (std::isfinite(length) && length > 0) {
      if (std::abs(length - 1) > kUnitTolerance) n /= length, ++rescaled;
      continue;
    }
    if (surface.empty()) {
      surface.assign(part.positions.size(), Vec3::Zero());
      for (const Face& f : part.faces) {
        const Vec3 a = (part.positions[f[1]] - part.positions[f[0]]).cross(part.positions[f[2]] - part.positions[f[0]]);
        for (int k = 0; k < 3; ++k) surface[f[k]] += a;
      }
    }
    const double s = v < surface.size() ? surface[v].norm() : 0;
    n = s > 0 ? Vec3(surface[v] / s) : Vec3(0, 0, 1);
    ++replaced;
  }
  const std::string where = path + ": " + (part.label.empty() ? "" : part.label + ": ");
  if (rescaled) warnings.push_back(where + std::to_string(rescaled) + " normals were not of unit length; normalized");
  if (replaced)
    warnings.push_back(where + std::to_string(replaced) + " normals were zero or not finite; replaced by the surface's");
}

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file (missing or unreadable)");
  // One read of the whole size: copying through `ss << in.rdbuf()` goes character by character in
  // libc++ (the wasm build), several seconds for a 36 MB file.
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) fail(path, "read error (cannot tell the file's size)");
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<size_t>(size), '\0');
  in.read(bytes.data(), size);
  if (in.gcount() != size) fail(path, "read error");
  return bytes;
}

void AtomicFileSet::add(const std::string& path, std::string bytes) {
  for (auto& f : files_)
    if (f.first == path) {
      f.second = std::move(bytes);
      return;
    }
  files_.emplace_back(path, std::move(bytes));
}

void AtomicFileSet::commit() {
  // Temporaries live in the target directory so that rename is atomic (same file system).
  static std::atomic<int> counter{0};
  std::vector<std::pair<fs::path, fs::path>> written;  // temporary, target
  auto cleanup = [&] {
    std::error_code ec;
    for (auto& w : written) fs::remove(w.first, ec);
  };
  for (auto& [target, bytes] : files_) {
    fs::path t(target);
    fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
      // A copied texture may sit in a sub-directory of the output; the output's own directory
      // must exist already (checked by writeDocument).
      fs::create_directories(dir, ec);
      if (ec) {
        cleanup();
        fail(target, "cannot create directory '" + dir.string() + "': " + ec.message());
      }
    }
    std::string name = ".";
    name += t.filename().string();
    name += ".geoshift-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".tmp";
    const fs::path tmp = dir / name;
    written.emplace_back(tmp, t);
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      cleanup();
      fail(target, "cannot create a file in '" + dir.string() + "'");
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      cleanup();
      fail(target, "write failed (disk full?)");
    }
  }
  for (size_t i = 0; i < written.size(); ++i) {
    std::error_code ec;
    fs::rename(written[i].first, written[i].second, ec);
    if (ec) {
      for (size_t j = i; j < written.size(); ++j) fs::remove(written[j].first, ec);
      fail(written[i].second.string(), "cannot replace the file: " + ec.message());
    }
  }
  files_.clear();
}

void checkPartSizes(const std::string& path, const MeshPart& part, size_t partIndex) {
  const size_t n = part.positions.size();
  const std::string where = "part " + std::to_string(partIndex) +
                            (part.label.empty() ? "" : " (" + part.label + ")");
  if (!part.normals.empty() && part.normals.size() != n)
    fail(path, where + " has " + std::to_string(part.normals.size()) + " normals for " +
                   std::to_string(n) + " positions");
  if (!part.colors.empty() && part.colors.size() != n)
    fail(path, where + " has " + std::to_string(part.colors.size()) + " colors for " +
                   std::to_string(n) + " positions");
  for (const auto& e : part.extras) {
    if (e.dim < 1 || e.dim > 4)
      fail(path, where + " extra attribute '" + e.name + "' has dimension " +
                     std::to_string(e.dim) + " (1 to 4 supported)");
    if (e.values.size() != n * static_cast<size_t>(e.dim))
      fail(path, where + " extra attribute '" + e.name + "' has " +
                     std::to_string(e.values.size()) + " values, expected " +
                     std::to_string(n * e.dim));
  }
  for (const auto& f : part.faces)
    for (int v : f)
      if (v < 0 || static_cast<size_t>(v) >= n)
        fail(path, where + " has a face index " + std::to_string(v) + " out of range (" +
                       std::to_string(n) + " positions)");
}

}  // namespace io

FileFormat formatFromPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".gltf") return FileFormat::Gltf;
  if (ext == ".glb") return FileFormat::Glb;
  if (ext == ".obj") return FileFormat::Obj;
  if (ext == ".off") return FileFormat::Off;
  if (ext == ".ply") return FileFormat::Ply;
  if (ext == ".stl") return FileFormat::Stl;
  io::fail(path, "unknown file extension '" + ext +
                     "'; geoshift reads and writes .gltf, .glb, .obj, .off, .ply and .stl");
}

namespace {

// A file whose first bytes are another format's signature was misnamed: say so rather than let
// the extension's reader report whatever the other format's bytes look like to it.
void checkSignature(const std::string& path, FileFormat format) {
  std::ifstream in(path, std::ios::binary);
  char head[5] = {};
  in.read(head, sizeof head);
  const std::string start(head, static_cast<size_t>(in.gcount()));
  const std::string ext = fs::path(path).extension().string();
  if (start.size() >= 4 && start.compare(0, 4, "glTF") == 0 && !io::isGltfFamily(format))
    io::fail(path, "the file is a binary glTF (it starts with 'glTF'), not a " + ext +
                       " file as its name says; rename it to .glb");
  if ((start.compare(0, 4, "ply\n") == 0 || start.compare(0, 5, "ply\r\n") == 0) && format != FileFormat::Ply)
    io::fail(path, "the file is a PLY file (its first line is 'ply'), not a " + ext +
                       " file as its name says; rename it to .ply");
}

}  // namespace

Document readDocument(const std::string& path, const ReadOptions& options) {
  const FileFormat format = formatFromPath(path);
  std::error_code ec;
  if (!fs::exists(path, ec)) io::fail(path, "file not found");
  if (fs::is_directory(path, ec)) io::fail(path, "is a directory, not a mesh file");
  if (fs::file_size(path, ec) == 0 && !ec) io::fail(path, "the file is empty (0 bytes)");
  checkSignature(path, format);
  Document doc;
  switch (format) {
    case FileFormat::Gltf:
    case FileFormat::Glb: doc = io::readGltf(path, format, options); break;
    case FileFormat::Obj: doc = io::readObj(path, options); break;
    case FileFormat::Off: doc = io::readOff(path, options); break;
    case FileFormat::Ply: doc = io::readPly(path, options); break;
    case FileFormat::Stl: doc = io::readStl(path, options); break;
  }
  for (MeshPart& part : doc.parts) io::unitNormals(path, part, doc.warnings);
  // An OBJ written back rewrites its vn lines only where the normals differ from these (so that a
  // round trip without changes is byte-identical, non-unit vn lines included).
  if (doc.source && doc.source->format == FileFormat::Obj) doc.source->obj.normals = doc.parts.front().normals;
  return doc;
}

std::vector<std::string> writeDocument(const Document& document, const std::string& path) {
  const FileFormat format = formatFromPath(path);
  const fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    io::fail(path, "output directory '" + dir.string() + "' does not exist");
  if (document.parts.empty()) io::fail(path, "nothing to write: the document has no mesh part");
  for (size_t i = 0; i < document.parts.size(); ++i)
    io::checkPartSizes(path, document.parts[i], i);

  const DocumentSource* src = document.source.get();
  const bool hasGltf = src && io::isGltfFamily(src->format);
  const bool hasObj = src && src->format == FileFormat::Obj;
  std::vector<std::string> warnings;
  if (io::isGltfFamily(format) && hasGltf) return io::writeGltfInto(document, path, format);
  if (format == FileFormat::Obj && hasObj) return io::writeObjInto(document, path);

  if (io::isGltfFamily(format)) warnings = io::writeGltfFresh(document, path, format);
  else if (format == FileFormat::Obj) warnings = io::writeObjFresh(document, path);
  else if (format == FileFormat::Ply) warnings = io::writePly(document, path);
  else if (format == FileFormat::Stl) warnings = io::writeStl(document, path);
  else warnings = io::writeOff(document, path);
  // OFF, PLY and STL hold nothing but what the parts carry: written back, nothing is lost.
  const bool sameSimple = src && src->format == format &&
                          (format == FileFormat::Off || format == FileFormat::Ply || format == FileFormat::Stl);
  if (src && !sameSimple) {
    warnings.push_back(path + ": written from a different format (" + document.path +
                       "): geometry, normals and colors only; materials, textures, texture "
                       "coordinates, groups and scene structure of the source were not carried over");
  }
  return warnings;
}

TriangleSoup partSoup(const MeshPart& part) { return {part.positions, part.faces}; }

TriangleSoup worldSoup(const Document& document) {
  TriangleSoup soup;
  static const std::vector<Eigen::Matrix4d> identity{Eigen::Matrix4d::Identity()};
  for (const auto& part : document.parts) {
    const auto& instances = part.instances.empty() ? identity : part.instances;
    for (const auto& m : instances) {
      const int offset = static_cast<int>(soup.positions.size());
      // A mirroring instance turns counter-clockwise faces clockwise; flip them back.
      const bool mirrored = m.topLeftCorner<3, 3>().determinant() < 0;
      for (const auto& p : part.positions)
        soup.positions.push_back((m * p.homogeneous()).hnormalized());
      for (const auto& f : part.faces)
        soup.faces.push_back(mirrored ? Face{f[0] + offset, f[2] + offset, f[1] + offset}
                                      : Face{f[0] + offset, f[1] + offset, f[2] + offset});
    }
  }
  return soup;
}

}  // namespace geoshift

#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift::cli {

ReadOptions& readOptions() {
  static ReadOptions options;
  return options;
}

Document load(const std::string& path) {
  Document doc = readDocument(path, readOptions());
  for (const std::string& w : doc.warnings) std::cerr << "geoshift: warning: " << w << "\n";
  return doc;
}

void save(const Document& doc, const std::string& path) {
  for (const std::string& w : writeDocument(doc, path)) std::cerr << "geoshift: warning: " << w << "\n";
}

namespace {

// "file: part" for messages, the part left out where it is only the file's name again (OBJ, OFF).
std::string where(const Document& doc, const MeshPart& part) {
  const std::string name = std::filesystem::path(doc.path).filename().string();
  return part.label.empty() || part.label == name ? doc.path : doc.path + ": " + part.label;
}

}  // namespace

MeshBuild buildPart(const Document& doc, const MeshPart& part) {
  MeshBuild b;
  try {
    b = buildMesh(partSoup(part));
  } catch (const InputError& e) {  // the core names the faces; the file and part are known here
    throw InputError(where(doc, part) + ": " + e.what());
  }
  for (const std::string& m : b.report.messages)
    std::cerr << "geoshift: note: " << where(doc, part) << ": " << m << "\n";
  return b;
}

void writeBack(MeshPart& part, const MeshBuild& build) {
  for (size_t i = 0; i < part.positions.size(); ++i) part.positions[i] = build.mesh.position(build.vertexOf[i]);
  if (part.normals.empty()) return;
  const MeshBuild own = buildMesh(partSoup(part), MeshBuildOptions::withoutWelding());
  const std::vector<Vec3> n = vertexNormals(own.mesh);
  for (size_t i = 0; i < part.normals.size(); ++i) {
    const Vec3& v = n[own.vertexOf[i]];
    // Vertices of dropped faces keep their normal rather than getting a zero one.
    if (v.squaredNorm() > 0) part.normals[i] = v;
  }
}

}  // namespace geoshift::cli

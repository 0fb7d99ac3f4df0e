#include <iostream>

#include "commands.hpp"
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

MeshBuild buildPart(const Document& doc, const MeshPart& part) {
  MeshBuild b = buildMesh(partSoup(part));
  for (const std::string& m : b.report.messages)
    std::cerr << "geoshift: note: " << doc.path << ": " << part.label << ": " << m << "\n";
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

// libFuzzer harness for mesh building and repair (buildMesh, Mesh::withTwins) on arbitrary soups
// (fuzz/soup_bytes.hpp): every soup is built welded (exactly and with a tolerance) and unwelded.
// An InputError is the expected outcome for bad indices, NaN/Inf or nothing left to build; a mesh
// that is built must satisfy the half-edge invariants below, or the harness traps (a defect, as
// is anything the sanitizers report).
#include <cstdint>
#include <vector>

#include "geoshift/error.hpp"
#include "geoshift/mesh.hpp"
#include "soup_bytes.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

// The invariants tests/native/test_mesh.cpp checks on hand-made meshes.
void checkConnectivity(const geoshift::Mesh& m) {
  using geoshift::Mesh;
  const int nv = m.vertexCount();
  for (const geoshift::Face& f : m.faces())
    for (int v : f) require(v >= 0 && v < nv);
  for (int h = 0; h < m.halfedgeCount(); ++h) {
    const int t = m.twin(h);
    if (t < 0) continue;
    require(t < m.halfedgeCount() && m.twin(t) == h && m.tail(t) == m.head(h) && m.head(t) == m.tail(h));
  }
  std::vector<int> corners(nv, 0);
  for (const geoshift::Face& f : m.faces())
    for (int v : f) ++corners[v];
  for (int v = 0; v < nv; ++v) {
    require((corners[v] == 0) == m.isIsolated(v));
    int visited = 0;
    m.forEachOutgoing(v, [&](int h) {
      require(m.tail(h) == v);
      require(++visited <= corners[v]);  // one fan: each face at v met once, and the walk ends
    });
    require(visited == corners[v]);
    require(m.originalVertex(v) >= 0 && m.originalVertex(v) < nv);
  }
}

void build(const geoshift::TriangleSoup& soup, const geoshift::MeshBuildOptions& options) {
  try {
    const geoshift::MeshBuild b = geoshift::buildMesh(soup, options);
    checkConnectivity(b.mesh);
    require(b.vertexOf.size() == soup.positions.size());
    for (int v : b.vertexOf) require(v >= 0 && v < b.mesh.vertexCount());
    require(b.report.inputFaces == static_cast<int>(soup.faces.size()));
    for (int f = 0; f < b.mesh.faceCount(); ++f)
      require(b.mesh.inputFace(f) >= 0 && b.mesh.inputFace(f) < static_cast<int>(soup.faces.size()));
    // The built mesh, given its own twins, is accepted as it is.
    std::vector<int> twins(b.mesh.halfedgeCount());
    for (int h = 0; h < b.mesh.halfedgeCount(); ++h) twins[h] = b.mesh.twin(h);
    const geoshift::Mesh again = geoshift::Mesh::withTwins(b.mesh.positions(), b.mesh.faces(), twins);
    require(again.vertexCount() == b.mesh.vertexCount());
    for (int h = 0; h < again.halfedgeCount(); ++h) require(again.twin(h) == b.mesh.twin(h));
  } catch (const geoshift::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const geoshift::TriangleSoup soup = geoshift::fuzz::soupFromBytes(data, size);
  build(soup, geoshift::MeshBuildOptions{});
  build(soup, geoshift::MeshBuildOptions::withoutWelding());
  geoshift::MeshBuildOptions loose;
  loose.weldOptions.tolerance = 0.3;  // merges neighbours of the 1/4 grid: faces collapse, fans pinch
  build(soup, loose);
  return 0;
}

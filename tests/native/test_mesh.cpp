#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

// The half-edge invariants every built mesh must satisfy, whatever the input was.
void checkConnectivity(const Mesh& m) {
  for (int h = 0; h < m.halfedgeCount(); ++h) {
    const int t = m.twin(h);
    if (t < 0) continue;
    REQUIRE(m.twin(t) == h);
    REQUIRE(m.tail(t) == m.head(h));
    REQUIRE(m.head(t) == m.tail(h));
  }
  std::vector<int> corners(m.vertexCount(), 0);
  for (const Face& f : m.faces())
    for (int v : f) ++corners[v];
  for (int v = 0; v < m.vertexCount(); ++v) {
    if (corners[v] == 0) {
      REQUIRE(m.isIsolated(v));
      continue;
    }
    // One fan per vertex: the rotation around v meets every face at v exactly once.
    int visited = 0;
    std::set<int> faces;
    m.forEachOutgoing(v, [&](int h) {
      REQUIRE(m.tail(h) == v);
      faces.insert(Mesh::faceOf(h));
      ++visited;
    });
    REQUIRE(visited == corners[v]);
    REQUIRE(static_cast<int>(faces.size()) == corners[v]);
    if (m.isBoundaryVertex(v)) REQUIRE(m.twin(m.halfedge(v)) < 0);
  }
}

int edgeCount(const Mesh& m) {
  int interior = 0, boundary = 0;
  for (int h = 0; h < m.halfedgeCount(); ++h) (m.twin(h) < 0 ? boundary : interior)++;
  return interior / 2 + boundary;
}

TriangleSoup soup(std::vector<Vec3> p, std::vector<Face> f) { return {std::move(p), std::move(f)}; }

}  // namespace

TEST_CASE("closed meshes have twins everywhere and Euler characteristic 2", "[mesh]") {
  for (const TriangleSoup& s : {shapes::tetrahedron(), shapes::cube(), shapes::icosphere(3)}) {
    MeshBuild b = buildMesh(s);
    const Mesh& m = b.mesh;
    checkConnectivity(m);
    REQUIRE(b.report.clean());
    REQUIRE(m.boundaryLoops().empty());
    for (int h = 0; h < m.halfedgeCount(); ++h) REQUIRE(m.twin(h) >= 0);
    REQUIRE(m.vertexCount() - edgeCount(m) + m.faceCount() == 2);
  }
}

TEST_CASE("a torus has Euler characteristic 0", "[mesh]") {
  const Mesh m = buildMesh(shapes::torus(24, 12)).mesh;
  checkConnectivity(m);
  REQUIRE(m.vertexCount() - edgeCount(m) + m.faceCount() == 0);
}

TEST_CASE("boundary loops of a grid and an open cylinder", "[mesh]") {
  const int n = 7;
  const Mesh grid = buildMesh(shapes::grid(n, 0.2)).mesh;
  checkConnectivity(grid);
  auto loops = grid.boundaryLoops();
  REQUIRE(loops.size() == 1);
  REQUIRE(loops[0].size() == static_cast<size_t>(4 * (n - 1)));
  int boundaryVertices = 0;
  for (int v = 0; v < grid.vertexCount(); ++v) boundaryVertices += grid.isBoundaryVertex(v);
  REQUIRE(boundaryVertices == 4 * (n - 1));
  // Consecutive loop vertices are joined by a boundary edge.
  for (size_t i = 0; i < loops[0].size(); ++i) {
    const int a = loops[0][i], b = loops[0][(i + 1) % loops[0].size()];
    bool found = false;
    grid.forEachOutgoing(a, [&](int h) { found |= grid.head(h) == b && grid.twin(h) < 0; });
    REQUIRE(found);
  }

  const Mesh cyl = buildMesh(shapes::cylinder(16, 5)).mesh;
  checkConnectivity(cyl);
  loops = cyl.boundaryLoops();
  REQUIRE(loops.size() == 2);
  REQUIRE(loops[0].size() == 16);
  REQUIRE(loops[1].size() == 16);
}

TEST_CASE("neighbors include both boundary neighbours", "[mesh]") {
  // A fan of two triangles around vertex 0: neighbours 1, 2, 3 in ccw order.
  const Mesh m = buildMesh(soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}}, {{0, 1, 2}, {0, 2, 3}})).mesh;
  REQUIRE(m.neighbors(0) == std::vector<int>{1, 2, 3});
  REQUIRE(m.isBoundaryVertex(0));
  REQUIRE(m.valence(2) == 3);
}

TEST_CASE("welding and the map back to the caller's layout round-trip exactly", "[mesh][weld]") {
  const TriangleSoup welded = shapes::cube();
  const TriangleSoup split = shapes::unwelded(welded);
  REQUIRE(split.positions.size() == 36);
  MeshBuild b = buildMesh(split);
  REQUIRE(b.mesh.vertexCount() == 8);
  REQUIRE(b.report.weldedVertices == 28);
  checkConnectivity(b.mesh);
  REQUIRE(b.mesh.boundaryLoops().empty());

  // positions: mesh -> caller gives back every caller position bit for bit
  std::vector<double> meshPos;
  for (const Vec3& p : b.mesh.positions()) meshPos.insert(meshPos.end(), {p.x(), p.y(), p.z()});
  const auto callerPos = toCallerLayout(meshPos, 3, b.vertexOf);
  for (size_t i = 0; i < split.positions.size(); ++i)
    for (int d = 0; d < 3; ++d) REQUIRE(callerPos[i * 3 + d] == split.positions[i][d]);

  // per-vertex values: caller -> mesh averages coincident vertices, mesh -> caller copies back
  std::vector<double> values(split.positions.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = b.vertexOf[i] * 10.0;
  const auto meshValues = toMeshLayout(values, 1, b.vertexOf, b.mesh);
  REQUIRE(toCallerLayout(meshValues, 1, b.vertexOf) == values);

  // unit vectors are averaged and re-normalised
  std::vector<double> dirs(split.positions.size() * 3, 0.0);
  for (size_t i = 0; i < split.positions.size(); ++i) dirs[i * 3 + (i % 3)] = 1.0;
  const auto meshDirs = toMeshLayout(dirs, 3, b.vertexOf, b.mesh, true);
  for (int v = 0; v < b.mesh.vertexCount(); ++v) {
    const Vec3 n(meshDirs[v * 3], meshDirs[v * 3 + 1], meshDirs[v * 3 + 2]);
    REQUIRE(n.norm() == Approx(1.0));
  }
}

TEST_CASE("welding with a tolerance merges near vertices, exact welding does not", "[mesh][weld]") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1e-7, 0, 0}, {1, 0, 0}, {-0.0, 0, 0}};
  Weld exact = weld(p);
  REQUIRE(exact.positions.size() == 3);  // -0 equals +0
  REQUIRE(exact.vertexOf == std::vector<int>{0, 1, 2, 0});
  Weld loose = weld(p, {1e-6});
  REQUIRE(loose.positions.size() == 2);
  REQUIRE(loose.vertexOf == std::vector<int>{0, 0, 1, 0});
  REQUIRE(loose.mergedCount == 2);
}

TEST_CASE("bad input is rejected with a message that names the culprit", "[mesh][errors]") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  REQUIRE_THROWS_WITH(buildMesh(soup({}, {})), Catch::Contains("empty mesh"));
  REQUIRE_THROWS_WITH(buildMesh(soup(p, {})), Catch::Contains("no faces"));
  REQUIRE_THROWS_WITH(buildMesh(soup(p, {{0, 1, 2}, {0, 2, 9}})),
                      Catch::Contains("face 1, corner 2: vertex index 9 is out of range (4 vertices)"));
  REQUIRE_THROWS_WITH(buildMesh(soup(p, {{0, -1, 2}})), Catch::Contains("vertex index -1"));
  auto q = p;
  q[2].y() = std::numeric_limits<double>::quiet_NaN();
  REQUIRE_THROWS_WITH(buildMesh(soup(q, {{0, 1, 2}})), Catch::Contains("vertex 2 has a non-finite coordinate"));
  q[2].y() = std::numeric_limits<double>::infinity();
  REQUIRE_THROWS_AS(buildMesh(soup(q, {{0, 1, 2}})), InputError);
  REQUIRE_THROWS_WITH(buildMesh(soup(p, {{0, 0, 1}, {1, 1, 2}})), Catch::Contains("no valid triangles"));
}

TEST_CASE("degenerate faces are dropped, counted and reported", "[mesh][errors]") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 1}};
  // face 1 repeats a vertex, face 2 has collinear corners
  MeshBuild b = buildMesh(soup(p, {{0, 1, 2}, {0, 0, 4}, {0, 1, 3}, {0, 4, 1}}));
  REQUIRE(b.mesh.faceCount() == 2);
  REQUIRE(b.report.repeatedIndexFaces == 1);
  REQUIRE(b.report.zeroAreaFaces == 1);
  REQUIRE(b.report.droppedFaces == std::vector<int>{1, 2});
  REQUIRE(b.mesh.inputFace(1) == 3);
  REQUIRE(b.report.messages.size() >= 2);
  REQUIRE_THAT(b.report.messages[0], Catch::Contains("face 1 (0, 0, 4)"));
  REQUIRE_THAT(b.report.messages[1], Catch::Contains("face 2 (0, 1, 3)"));
  // vertex 3 is used only by the dropped face: isolated, kept
  REQUIRE(b.mesh.vertexCount() == 5);
  REQUIRE(b.mesh.isIsolated(3));
  REQUIRE(b.report.isolatedVertices == 1);
  checkConnectivity(b.mesh);
  // a needle is not degenerate
  MeshBuild needle = buildMesh(soup({{0, 0, 0}, {1, 0, 0}, {0.5, 1e-5, 0}}, {{0, 1, 2}}));
  REQUIRE(needle.mesh.faceCount() == 1);
  // Far outside double precision's range for areas (1e100: infinite areas; 1e-100: every face of
  // zero area) the mesh is refused with its size.
  for (const double scale : {1e30, 1e-30, 1e100, 1e-100}) {
    const std::vector<Vec3> t = {{0, 0, 0}, {scale, 0, 0}, {0, scale, 0}};
    CAPTURE(scale);
    if (scale > 1e-75 && scale < 1e75) {
      REQUIRE(buildMesh(soup(t, {{0, 1, 2}})).mesh.faceCount() == 1);
    } else {
      REQUIRE_THROWS_WITH(buildMesh(soup(t, {{0, 1, 2}})),
                          Catch::Contains("the faces span 1e") && Catch::Contains(scale > 1 ? "scale the mesh down" : "scale the mesh up"));
    }
  }
  // Far-off coordinates are fine where the faces' extent is: only the differences are squared.
  std::vector<Vec3> far = {{1e200, 0, 0}, {1e200 + 1e185, 0, 0}, {1e200, 1e185, 0}};
  REQUIRE_THROWS_WITH(buildMesh(soup(far, {{0, 1, 2}})), Catch::Contains("the faces span 1") && Catch::Contains("e+185 "));
  far = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e200, 0, 0}};  // a vertex no face uses is not counted
  REQUIRE(buildMesh(soup(far, {{0, 1, 2}})).mesh.faceCount() == 1);
}

TEST_CASE("an edge with three faces is cut, never a crash", "[mesh][nonmanifold]") {
  // Three triangles hinge on edge 0-1 (a fin).
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  MeshBuild b = buildMesh(soup(p, {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}}));
  REQUIRE(b.report.nonManifoldEdges == 1);
  REQUIRE_THAT(b.report.messages[0], Catch::Contains("edge 0-1") || Catch::Contains("edge 1-0"));
  checkConnectivity(b.mesh);
  REQUIRE(b.mesh.faceCount() == 3);
  // The fin that was cut off makes vertices 0 and 1 non-manifold; they are split.
  REQUIRE(b.report.nonManifoldVertices == 2);
  REQUIRE(b.mesh.vertexCount() == 7);
  for (int v = 5; v < 7; ++v) REQUIRE(b.mesh.position(v) == b.mesh.position(b.mesh.originalVertex(v)));
  // Callers 0 and 1 are shared by the two faces that stay joined and the one cut off: they follow
  // the piece with two of their faces, in whatever order the faces come, so that the lone face
  // cannot move them.
  for (const std::vector<Face>& faces : {std::vector<Face>{{0, 1, 2}, {1, 0, 3}, {1, 0, 4}},
                                         std::vector<Face>{{1, 0, 4}, {0, 1, 2}, {1, 0, 3}},
                                         std::vector<Face>{{1, 0, 3}, {1, 0, 4}, {0, 1, 2}}}) {
    MeshBuild c = buildMesh(soup(p, faces));
    REQUIRE(c.mesh.vertexCount() == 7);
    for (int caller : {0, 1}) {
      const int v = c.vertexOf[caller];
      int incident = 0;
      for (int f = 0; f < c.mesh.faceCount(); ++f) incident += std::ranges::count(c.mesh.face(f), v);
      CAPTURE(caller, v);
      REQUIRE(incident == 2);
    }
  }
}

TEST_CASE("a face of opposite orientation to its neighbour is flipped and the edge joined", "[mesh][orientation]") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}};
  MeshBuild b = buildMesh(soup(p, {{0, 1, 2}, {0, 1, 3}}));
  REQUIRE(b.report.reorientedFaces == 1);
  REQUIRE(b.report.nonManifoldEdges == 0);
  REQUIRE_FALSE(b.report.clean());
  checkConnectivity(b.mesh);
  // On a tie the first face keeps its orientation; the second turns to agree with it.
  REQUIRE(b.mesh.face(0) == Face{0, 1, 2});
  REQUIRE(b.mesh.face(1) == Face{0, 3, 1});
  REQUIRE(faceNormals(b.mesh)[0].dot(faceNormals(b.mesh)[1]) > 0.99);
  int joined = 0;
  for (int h = 0; h < b.mesh.halfedgeCount(); ++h) joined += b.mesh.twin(h) >= 0;
  REQUIRE(joined == 2);
}

TEST_CASE("a closed surface wound inconsistently is re-oriented to its majority", "[mesh][orientation]") {
  const TriangleSoup sphere = shapes::icosphere(2);
  const MeshBuild reference = buildMesh(sphere);
  REQUIRE(reference.report.clean());
  for (const int every : {7, 2}) {  // a seventh of the faces flipped, then half of them
    TriangleSoup mixed = sphere;
    int flips = 0;
    for (size_t f = 0; f < mixed.faces.size(); f += every, ++flips) std::swap(mixed.faces[f][1], mixed.faces[f][2]);
    const MeshBuild b = buildMesh(mixed);
    CAPTURE(every);
    REQUIRE(b.report.reorientedFaces == std::min<int>(flips, static_cast<int>(sphere.faces.size()) - flips));
    REQUIRE(b.report.nonManifoldEdges == 0);
    REQUIRE(b.report.nonManifoldVertices == 0);
    checkConnectivity(b.mesh);
    REQUIRE(b.mesh.boundaryLoops().empty());
    // Each caller vertex maps to its own mesh vertex, and each mesh corner to the caller's corner
    // it came from, whichever way its face was turned.
    for (size_t i = 0; i < mixed.positions.size(); ++i) REQUIRE(b.mesh.position(b.vertexOf[i]) == mixed.positions[i]);
    int turned = 0;
    for (int f = 0; f < b.mesh.faceCount(); ++f) {
      const Face& given = mixed.faces[b.mesh.inputFace(f)];
      turned += b.mesh.inputFlipped(f);
      for (int k = 0; k < 3; ++k) REQUIRE(b.mesh.face(f)[k] == b.vertexOf[given[b.mesh.inputCorner(f, k)]]);
      const Vec3 bary(0.2, 0.3, 0.5);
      REQUIRE(b.mesh.inputCornerOrder(f, b.mesh.inputCornerOrder(f, bary)) == bary);
    }
    REQUIRE(turned == b.report.reorientedFaces);
    if (every == 7) {
      // The flipped faces are turned back: the mesh is the consistently wound one, face for face.
      REQUIRE(b.mesh.faces() == reference.mesh.faces());
    } else {
      // Half flipped, the other half kept: a tie, so the first face's (flipped) orientation wins
      // and every face ends reversed against the reference, consistently.
      for (int f = 0; f < b.mesh.faceCount(); ++f)
        REQUIRE(faceNormals(b.mesh)[f].dot(faceNormals(reference.mesh)[f]) < -0.99);
    }
  }
  // Most faces flipped: the piece takes their orientation and the few others turn.
  TriangleSoup most = sphere;
  for (size_t f = 0; f < most.faces.size(); ++f)
    if (f % 5 != 0) std::swap(most.faces[f][1], most.faces[f][2]);
  const MeshBuild m = buildMesh(most);
  REQUIRE(m.report.reorientedFaces == static_cast<int>((sphere.faces.size() + 4) / 5));
  for (int f = 0; f < m.mesh.faceCount(); ++f) REQUIRE(faceNormals(m.mesh)[f].dot(faceNormals(reference.mesh)[f]) < -0.99);
}

TEST_CASE("a Moebius strip cannot be oriented: the disagreeing edge is cut as before", "[mesh][orientation]") {
  // A strip of 2n triangles around a circle, given a half turn, so that its ends meet reversed.
  const int n = 12;
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, t = a / 2;
    const Vec3 centre(std::cos(a), std::sin(a), 0), radial = centre, up(0, 0, 1);
    const Vec3 across = 0.3 * (std::cos(t) * radial + std::sin(t) * up);
    p.push_back(centre + across);
    p.push_back(centre - across);
  }
  std::vector<Face> faces;
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    int c = 2 * ((i + 1) % n), d = c + 1;
    if (i == n - 1) std::swap(c, d);  // the half turn: the last quad joins the first one's vertices swapped
    faces.push_back({a, b, d});
    faces.push_back({a, d, c});
  }
  const MeshBuild b = buildMesh(soup(p, faces));
  REQUIRE(b.report.nonManifoldEdges >= 1);
  checkConnectivity(b.mesh);
  REQUIRE(b.mesh.faceCount() == 2 * n);
}

TEST_CASE("a vertex shared by two fans is split and the caller map follows the faces", "[mesh][nonmanifold]") {
  // Two triangles that touch only at the origin (a bow tie), given with separate caller vertices
  // for each triangle's copy of the origin, so welding creates the non-manifold vertex.
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {-1, 0, 0}, {-1, -1, 0}};
  MeshBuild b = buildMesh(soup(p, {{0, 1, 2}, {3, 4, 5}}));
  REQUIRE(b.report.weldedVertices == 1);
  REQUIRE(b.report.nonManifoldVertices == 1);
  REQUIRE(b.report.splitVertexCopies == 1);
  REQUIRE(b.mesh.vertexCount() == 6);
  checkConnectivity(b.mesh);
  REQUIRE(b.vertexOf[0] != b.vertexOf[3]);
  REQUIRE(b.mesh.originalVertex(b.vertexOf[3]) == b.vertexOf[0]);
  REQUIRE(b.mesh.boundaryLoops().size() == 2);

  // The same bow tie with one caller vertex at the origin: the pieces hold one face each, and the
  // tie goes to the original vertex, not to its copy.
  MeshBuild shared = buildMesh(soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}));
  REQUIRE(shared.report.nonManifoldVertices == 1);
  REQUIRE(shared.mesh.vertexCount() == 6);
  REQUIRE(shared.vertexOf[0] == 0);
  REQUIRE(shared.mesh.originalVertex(5) == 0);

  // Two tetrahedra sharing a vertex: both closed, the shared vertex split.
  TriangleSoup t = shapes::tetrahedron();
  const size_t n = t.positions.size(), m = t.faces.size();
  const Vec3 apex = t.positions[0];
  for (size_t i = 0; i < n; ++i) t.positions.push_back(2 * apex - t.positions[i]);
  for (size_t f = 0; f < m; ++f) {
    Face g = t.faces[f];
    for (int& i : g) i += static_cast<int>(n);
    std::swap(g[1], g[2]);  // the point reflection flips orientation; undo it
    t.faces.push_back(g);
  }
  MeshBuild two = buildMesh(t);
  REQUIRE(two.report.nonManifoldVertices == 1);
  REQUIRE(two.report.nonManifoldEdges == 0);
  checkConnectivity(two.mesh);
  REQUIRE(two.mesh.boundaryLoops().empty());
}

TEST_CASE("many faces on one vertex and duplicate faces do not break the build", "[mesh][nonmanifold]") {
  // A "book" of 6 pages sharing the spine 0-1, plus an exact duplicate of one page.
  std::vector<Vec3> p = {{0, 0, 0}, {0, 0, 1}};
  std::vector<Face> f;
  for (int i = 0; i < 6; ++i) {
    const double a = i * M_PI / 3;
    p.push_back({std::cos(a), std::sin(a), 0.5});
    f.push_back({0, 1, static_cast<int>(p.size()) - 1});
  }
  f.push_back(f[0]);
  MeshBuild b = buildMesh(soup(p, f));
  // the spine, and the two other edges of the duplicated page
  REQUIRE(b.report.nonManifoldEdges == 3);
  checkConnectivity(b.mesh);
}

TEST_CASE("a mesh from given twins equals the constructor's; bad twins are refused", "[mesh][twins]") {
  for (const TriangleSoup& s : {shapes::icosphere(2), shapes::grid(7, 0.2, 5), shapes::cylinder(9, 4)}) {
    const Mesh built = buildMesh(s).mesh;
    std::vector<int> twins(built.halfedgeCount());
    for (int h = 0; h < built.halfedgeCount(); ++h) twins[h] = built.twin(h);
    const Mesh m = Mesh::withTwins(built.positions(), built.faces(), twins);
    checkConnectivity(m);
    REQUIRE(m.vertexCount() == built.vertexCount());
    REQUIRE(m.faces() == built.faces());
    for (int h = 0; h < m.halfedgeCount(); ++h) REQUIRE(m.twin(h) == built.twin(h));
    // The same start half-edge per vertex, so every walk around a vertex visits in the same order.
    for (int v = 0; v < m.vertexCount(); ++v) REQUIRE(m.halfedge(v) == built.halfedge(v));
    for (int f = 0; f < m.faceCount(); ++f) REQUIRE(m.inputFace(f) == f);
  }

  const Mesh ico = buildMesh(shapes::icosphere(0)).mesh;
  std::vector<int> twins(ico.halfedgeCount());
  for (int h = 0; h < ico.halfedgeCount(); ++h) twins[h] = ico.twin(h);
  auto attempt = [&](std::vector<int> t, std::vector<Face> faces) { Mesh::withTwins(ico.positions(), faces, t); };
  REQUIRE_THROWS_WITH(attempt({0, 1}, ico.faces()), Catch::Contains("2 twins for"));
  std::vector<int> oneSided = twins;
  oneSided[twins[0]] = -1;  // 0 still names its twin, which no longer names 0
  REQUIRE_THROWS_WITH(attempt(oneSided, ico.faces()), Catch::Contains("half-edge 0 ("));
  std::vector<int> wrong = twins;
  std::swap(wrong[0], wrong[1]);  // mutual no more, and pointing at edges of other vertices
  REQUIRE_THROWS_AS(attempt(wrong, ico.faces()), InputError);
  std::vector<Face> degenerate = ico.faces();
  degenerate[3] = {degenerate[3][0], degenerate[3][0], degenerate[3][1]};
  REQUIRE_THROWS_WITH(attempt(twins, degenerate), Catch::Contains("face 3") && Catch::Contains("degenerate"));
}

// --- renumbering ------------------------------------------------------------------------------------

namespace {

// A random renumbering of the mesh's vertices and faces.
Renumbering shuffled(const Mesh& m, unsigned seed) {
  std::mt19937 rng(seed);
  Renumbering r;
  r.newVertex.resize(m.vertexCount());
  r.newFace.resize(m.faceCount());
  std::iota(r.newVertex.begin(), r.newVertex.end(), 0);
  std::iota(r.newFace.begin(), r.newFace.end(), 0);
  std::shuffle(r.newVertex.begin(), r.newVertex.end(), rng);
  std::shuffle(r.newFace.begin(), r.newFace.end(), rng);
  return r;
}

// Everything a mesh holds, element by element, so that two meshes compare to the bit.
struct Held {
  std::vector<Vec3> positions;
  std::vector<Face> faces;
  std::vector<int> inputFace, twin, halfedge, original;
  bool operator==(const Held&) const = default;
};
Held held(const Mesh& m) {
  Held h{m.positions(), m.faces(), {}, {}, {}, {}};
  for (int f = 0; f < m.faceCount(); ++f) h.inputFace.push_back(m.inputFlipped(f) ? -1 - m.inputFace(f) : m.inputFace(f));
  for (int e = 0; e < m.halfedgeCount(); ++e) h.twin.push_back(m.twin(e));
  for (int v = 0; v < m.vertexCount(); ++v) {
    h.halfedge.push_back(m.halfedge(v));
    h.original.push_back(m.originalVertex(v));
  }
  return h;
}

// A mesh with every kind of element a build can leave: a boundary, a face turned over, a vertex
// split at a non-manifold edge (a fin) and an isolated vertex.
Mesh awkwardMesh() {
  TriangleSoup s = shapes::grid(6, 0.1, 2);
  const int n = static_cast<int>(s.positions.size());
  s.faces[7] = {s.faces[7][0], s.faces[7][2], s.faces[7][1]};  // wound backwards: turned by the build
  // A third face on the diagonal the first two faces share: a fin.
  std::vector<int> shared;
  for (int a : s.faces[0])
    if (std::ranges::count(s.faces[1], a)) shared.push_back(a);
  REQUIRE(shared.size() == 2);
  s.positions.push_back(Vec3(0.3, 0.2, 0.5));
  s.faces.push_back({shared[0], shared[1], n});
  s.positions.push_back(Vec3(5, 5, 5));        // isolated
  MeshBuild b = buildMesh(s);
  REQUIRE(b.report.reorientedFaces > 0);
  REQUIRE(b.report.splitVertexCopies > 0);
  REQUIRE(b.report.isolatedVertices == 1);
  return std::move(b.mesh);
}

}  // namespace

TEST_CASE("a renumbered mesh walks the same elements in the same order, and renumbering back restores every bit",
          "[mesh][renumber]") {
  for (const Mesh& m : {awkwardMesh(), buildMesh(shapes::torus(24, 12)).mesh}) {
    Renumbering r = shuffled(m, 5);
    const Renumbering copy = r;
    REQUIRE(isRenumbering(m, r));
    Mesh n = m;
    n.renumber(r);
    REQUIRE(r.newVertex == copy.newVertex);  // the scratch marks are undone
    REQUIRE(r.newFace == copy.newFace);
    checkConnectivity(n);
    const std::vector<int>& nv = r.newVertex;
    auto newHalfedge = [&](int h) { return h < 0 ? h : 3 * r.newFace[h / 3] + h % 3; };
    for (int v = 0; v < m.vertexCount(); ++v) {
      CAPTURE(v);
      REQUIRE(n.position(nv[v]) == m.position(v));
      REQUIRE(n.halfedge(nv[v]) == newHalfedge(m.halfedge(v)));
      REQUIRE(n.isBoundaryVertex(nv[v]) == m.isBoundaryVertex(v));
      REQUIRE(n.originalVertex(nv[v]) == nv[m.originalVertex(v)]);
      std::vector<int> ring = m.neighbors(v);
      for (int& u : ring) u = nv[u];
      REQUIRE(n.neighbors(nv[v]) == ring);  // the same neighbours in the same order
    }
    for (int f = 0; f < m.faceCount(); ++f) {
      CAPTURE(f);
      const int g = r.newFace[f];
      REQUIRE(n.face(g) == Face{nv[m.face(f)[0]], nv[m.face(f)[1]], nv[m.face(f)[2]]});
      REQUIRE(n.inputFace(g) == m.inputFace(f));
      REQUIRE(n.inputFlipped(g) == m.inputFlipped(f));
      for (int k = 0; k < 3; ++k) REQUIRE(n.twin(3 * g + k) == newHalfedge(m.twin(3 * f + k)));
    }
    invert(r);
    for (int v = 0; v < m.vertexCount(); ++v) REQUIRE(r.newVertex[copy.newVertex[v]] == v);
    for (int f = 0; f < m.faceCount(); ++f) REQUIRE(r.newFace[copy.newFace[f]] == f);
    n.renumber(r);
    REQUIRE(held(n) == held(m));
    invert(r);
    REQUIRE(r.newVertex == copy.newVertex);
    REQUIRE(r.newFace == copy.newFace);

    // Back by the input faces: every face of these meshes is its own input face.
    for (int f = 0; f < m.faceCount(); ++f) REQUIRE(m.inputFace(f) == f);
    n.renumber(r);
    invert(r);
    r.newFace.clear();
    n.renumber(r);
    REQUIRE(held(n) == held(m));
  }
  Renumbering wrong = shuffled(awkwardMesh(), 1);
  wrong.newVertex[0] = wrong.newVertex[1];
  REQUIRE_FALSE(isRenumbering(awkwardMesh(), wrong));
  wrong = shuffled(awkwardMesh(), 1);
  wrong.newFace.pop_back();
  REQUIRE_FALSE(isRenumbering(awkwardMesh(), wrong));
}

TEST_CASE("spatial order puts neighbours near one another in index", "[mesh][renumber]") {
  // A torus in a random order: its edges join vertices about a third of the mesh apart in index.
  Mesh m = buildMesh(shapes::torus(96, 48)).mesh;
  Renumbering scramble = shuffled(m, 9);
  m.renumber(scramble);
  auto meanGap = [](const Mesh& mesh) {
    double sum = 0;
    for (int h = 0; h < mesh.halfedgeCount(); ++h) sum += std::abs(mesh.tail(h) - mesh.head(h));
    return sum / mesh.halfedgeCount() / mesh.vertexCount();
  };
  auto meanFaceGap = [](const Mesh& mesh) {
    double sum = 0;
    for (int h = 0; h < mesh.halfedgeCount(); ++h) sum += std::abs(Mesh::faceOf(h) - Mesh::faceOf(mesh.twin(h)));
    return sum / mesh.halfedgeCount() / mesh.faceCount();
  };
  const double before = meanGap(m), faceBefore = meanFaceGap(m);
  Renumbering r = spatialOrder(m);
  REQUIRE(isRenumbering(m, r));
  m.renumber(r);
  const double after = meanGap(m), faceAfter = meanFaceGap(m);
  INFO("vertex gap " << before << " -> " << after << ", face gap " << faceBefore << " -> " << faceAfter);
  REQUIRE(before > 0.3);
  REQUIRE(after < 0.03);
  REQUIRE(faceAfter < 0.03);
  // Faces come in the order of their lowest corner.
  for (int f = 1; f < m.faceCount(); ++f) {
    const Face& a = m.face(f - 1);
    const Face& b = m.face(f);
    REQUIRE(std::min({a[0], a[1], a[2]}) <= std::min({b[0], b[1], b[2]}));
  }
  // The order depends on the positions alone: the same mesh in another order gets the same one.
  Mesh again = m;
  Renumbering other = shuffled(again, 3);
  again.renumber(other);
  Renumbering r2 = spatialOrder(again);
  again.renumber(r2);
  REQUIRE(again.positions() == m.positions());
}

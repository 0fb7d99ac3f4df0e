#pragma once
// Triangle mesh with half-edge connectivity, built from indexed triangles.
//
// Half-edges are implicit in the face corners: half-edge h = 3f + k runs from face(f)[k] to
// face(f)[(k+1) % 3], so next/prev/face are arithmetic and only the twins are stored. Faces are
// counter-clockwise seen from outside. After construction every vertex has a single fan of faces
// (non-manifold input is split into manifold pieces) and every edge at most two faces.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products are everywhere on meshes

namespace geoshift {

using Vec3 = Eigen::Vector3d;
using Face = std::array<int, 3>;

// What a caller passes in: positions and triangles in the caller's own vertex layout.
struct TriangleSoup {
  std::vector<Vec3> positions;
  std::vector<Face> faces;
};

// What construction found and repaired. Every count has a message in `messages` that names the
// offending indices (the first few of them, with the total).
struct BuildReport {
  int inputVertices = 0;
  int inputFaces = 0;
  int weldedVertices = 0;          // caller vertices merged into an earlier coincident one
  int repeatedIndexFaces = 0;      // dropped: a face that uses one vertex twice
  int zeroAreaFaces = 0;           // dropped: collinear corners
  std::vector<int> droppedFaces;   // input face indices of the two kinds above
  int reorientedFaces = 0;         // flipped to agree with their neighbours (the piece's majority kept)
  int nonManifoldEdges = 0;        // edges with more than two faces, or of two faces left disagreeing: cut
  int nonManifoldVertices = 0;     // vertices whose faces form several fans: split
  int splitVertexCopies = 0;       // vertices added by that split
  int isolatedVertices = 0;        // referenced by no face: kept, left untouched by filters
  std::vector<std::string> messages;

  bool clean() const {
    return repeatedIndexFaces == 0 && zeroAreaFaces == 0 && reorientedFaces == 0 && nonManifoldEdges == 0 &&
           nonManifoldVertices == 0;
  }
};

struct Renumbering;

class Mesh {
 public:
  Mesh() = default;

  // Builds connectivity from positions and triangles as given (no welding).
  // Throws InputError when there is no vertex or no face, a coordinate is NaN/Inf (naming the
  // vertex), or an index is out of range (naming the face and the corner). Degenerate faces are
  // dropped and non-manifold configurations split, as counted in `report` when given.
  Mesh(std::vector<Vec3> positions, const std::vector<Face>& faces, BuildReport* report = nullptr);

  // The same mesh from faces whose half-edges are already paired (e.g. a coarsening of a Mesh that
  // kept its twins): twins[3f + k] is the opposite half-edge or -1 on the boundary. Skips the edge
  // sort of the constructor, most of its time on large meshes; fans, split copies and `report` as
  // there. Throws InputError as the constructor does, and when twins has another size than
  // 3 x faces, a pair is not mutual or its half-edges do not run opposite ways (naming the
  // half-edge), or a face is degenerate (it cannot be dropped under given twins; naming the face).
  static Mesh withTwins(std::vector<Vec3> positions, std::vector<Face> faces, std::vector<int> twins,
                        BuildReport* report = nullptr);

  int vertexCount() const { return static_cast<int>(positions_.size()); }
  int faceCount() const { return static_cast<int>(faces_.size()); }
  int halfedgeCount() const { return 3 * faceCount(); }

  const Vec3& position(int v) const { return positions_[v]; }
  Vec3& position(int v) { return positions_[v]; }
  const std::vector<Vec3>& positions() const { return positions_; }
  // Geometry may change; connectivity may not.
  std::vector<Vec3>& positions() { return positions_; }
  const Face& face(int f) const { return faces_[f]; }
  const std::vector<Face>& faces() const { return faces_; }
  // The caller's face index of mesh face f (faces may have been dropped).
  int inputFace(int f) const { return inputFace_[f] < 0 ? -1 - inputFace_[f] : inputFace_[f]; }
  // Whether mesh face f is the caller's face turned over to agree with its neighbours
  // (BuildReport::reorientedFaces): then its corners 1 and 2 are the caller's 2 and 1.
  bool inputFlipped(int f) const { return inputFace_[f] < 0; }
  // The caller's corner (0, 1, 2 of its face inputFace(f)) that mesh face f has as corner k.
  int inputCorner(int f, int k) const { return inputFlipped(f) && k > 0 ? 3 - k : k; }
  // Per-corner values of mesh face f (barycentric coordinates) in the caller's corner order, or the
  // caller's in the mesh's: the same swap either way.
  Vec3 inputCornerOrder(int f, const Vec3& perCorner) const {
    return inputFlipped(f) ? Vec3(perCorner[0], perCorner[2], perCorner[1]) : perCorner;
  }

  // --- half-edges ---
  static int faceOf(int h) { return h / 3; }
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  int tail(int h) const { return faces_[h / 3][h % 3]; }
  int head(int h) const { return faces_[h / 3][(h % 3 + 1) % 3]; }
  // The opposite half-edge, or -1 on the boundary.
  int twin(int h) const { return twin_[h]; }
  bool isBoundaryHalfedge(int h) const { return twin_[h] < 0; }

  // One outgoing half-edge of v; for a boundary vertex the one on the boundary (twin -1), so that
  // a counter-clockwise walk with ccwOutgoing meets every face. -1 for an isolated vertex.
  int halfedge(int v) const { return vertexHalfedge_[v]; }
  bool isIsolated(int v) const { return vertexHalfedge_[v] < 0; }
  bool isBoundaryVertex(int v) const {
    return vertexHalfedge_[v] >= 0 && twin_[vertexHalfedge_[v]] < 0;
  }
  // Next outgoing half-edge counter-clockwise around tail(h), or -1 past the last boundary face.
  int ccwOutgoing(int h) const { return twin_[prev(h)]; }

  // Calls f(h) for every outgoing half-edge of v, counter-clockwise, starting at halfedge(v).
  template <class F>
  void forEachOutgoing(int v, F&& f) const {
    const int start = vertexHalfedge_[v];
    if (start < 0) return;
    int h = start;
    do {
      f(h);
      h = ccwOutgoing(h);
    } while (h >= 0 && h != start);
  }
  // Neighbouring vertices of v, counter-clockwise; on the boundary both end neighbours included.
  std::vector<int> neighbors(int v) const;
  int valence(int v) const { return static_cast<int>(neighbors(v).size()); }

  // Boundary loops as vertex sequences, each following its boundary half-edges.
  std::vector<std::vector<int>> boundaryLoops() const;

  // The vertex a split copy was made from (itself for every other vertex).
  int originalVertex(int v) const { return originalVertex_[v]; }

  // Renumbers the vertices and faces: vertex v becomes r.newVertex[v] and face f becomes
  // r.newFace[f], its corners, half-edges and twins following, so every walk (a vertex's
  // outgoing half-edges, its neighbours) visits the same elements in the same order under their
  // new numbers. In place and without allocating, so it cannot throw: r serves as scratch and is
  // the same when it returns. r must be a renumbering of this mesh (isRenumbering). With
  // r.newFace empty, face f becomes inputFace(f) instead, which must then be a permutation of the
  // faces: it puts back the faces of a mesh built without dropping any (inputFace(f) == f) after
  // they were renumbered, with no array to keep for them.
  void renumber(Renumbering& r) noexcept;

 private:
  // Vertex half-edges, splitting a vertex whose faces form several fans (one copy per extra fan).
  void buildFans(BuildReport& r);
  std::vector<int> orientCoherently(std::vector<std::pair<std::uint64_t, int>>& edges);

  std::vector<Vec3> positions_;
  std::vector<Face> faces_;
  std::vector<int> inputFace_;  // -1 - index for a face turned over (inputFlipped)
  std::vector<int> twin_;
  std::vector<int> vertexHalfedge_;
  std::vector<int> originalVertex_;
};

// A renumbering of a mesh's vertices and faces: newVertex[v] and newFace[f] the new indices, each
// a permutation.
struct Renumbering {
  std::vector<int> newVertex;
  std::vector<int> newFace;
};

// Whether r is a renumbering of the mesh: permutations of its vertex and face counts.
bool isRenumbering(const Mesh& mesh, const Renumbering& r);

// Turns r into the renumbering that undoes it, in place and without allocating.
void invert(Renumbering& r) noexcept;

// The new index of each vertex in the Morton (Z-curve) order of the positions, quantised to 21 bits
// an axis over the bounding box of the finite ones, ties in index order; a coordinate that is not
// finite goes to the lowest or highest cell (only locality is at stake, any order is correct).
std::vector<int> mortonOrder(const Mesh& mesh);

// Vertices in Morton order (mortonOrder); faces by their lowest new corner, ties in index order.
// Elements near one another in space get indices near one another, so that walks over
// neighbourhoods read nearby memory (docs/denoising.md#speed-and-memory, spatial order).
Renumbering spatialOrder(const Mesh& mesh);

// The connected pieces of a mesh: vertices joined through faces (after the build's repairs, so a
// fin cut off a non-manifold edge is a piece of its own).
struct Pieces {
  std::vector<int> pieceOf;  // per vertex: its piece, numbered by lowest vertex; -1 for an isolated vertex
  std::vector<int> vertexCount;  // per piece
};
Pieces pieces(const Mesh& mesh);

// --- welding -----------------------------------------------------------------------------------

struct WeldOptions {
  // Positions closer than this are merged; 0 merges only exactly equal positions (what glTF's
  // seam splits produce). Absolute, in the mesh's units.
  double tolerance = 0.0;
};

struct Weld {
  std::vector<Vec3> positions;   // one per welded vertex, the first caller vertex's position
  std::vector<int> vertexOf;     // caller vertex -> welded vertex
  int mergedCount = 0;
};

// Merges coincident vertices. Deterministic: welded vertices are numbered in order of their
// first caller vertex. Throws InputError on NaN/Inf coordinates (naming the vertex).
Weld weld(const std::vector<Vec3>& positions, const WeldOptions& options = {});

struct MeshBuildOptions {
  bool weld = true;
  WeldOptions weldOptions;

  // Connectivity exactly as the caller gave it (hard edges stay split).
  static MeshBuildOptions withoutWelding() {
    MeshBuildOptions o;
    o.weld = false;
    return o;
  }
};

// A mesh built from a caller's soup, with the map back to the caller's vertex layout so that
// per-vertex results can be written back one for one.
struct MeshBuild {
  Mesh mesh;
  std::vector<int> vertexOf;  // caller vertex -> mesh vertex
  BuildReport report;
};

// Validates the soup (InputError naming face/index/vertex on bad indices, NaN/Inf, empty input),
// welds, then builds the mesh. Degenerate and non-manifold configurations are repaired and reported.
MeshBuild buildMesh(const TriangleSoup& soup, const MeshBuildOptions& options = {});

// Per-mesh-vertex values -> per-caller-vertex values (rows of `dim` numbers each).
std::vector<double> toCallerLayout(const std::vector<double>& meshValues, int dim,
                                   const std::vector<int>& vertexOf);
// Per-caller-vertex values -> per-mesh-vertex values: the mean of the caller vertices that were
// welded together (re-normalised when `unitVectors`). Mesh vertices with no caller vertex (split
// copies) take the value of their original vertex.
std::vector<double> toMeshLayout(const std::vector<double>& callerValues, int dim,
                                 const std::vector<int>& vertexOf, const Mesh& mesh,
                                 bool unitVectors = false);

}  // namespace geoshift

#pragma once
// Vertex positions from target face normals (Lee–Wang 2005; Sun et al. 2007; docs/algorithms.md#vertex-update):
// the second half of every normal-filtering denoiser.
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

// What the flip guard compares each face's candidate normal with (besides its current normal).
enum class FlipGuard {
  Input,           // its input normal: no face ends up flipped relative to the input
  InputOrTarget,   // its input or its target normal: folds in noisy input may unfold
};

struct VertexUpdatePlan;

struct VertexUpdateOptions {
  int iterations = 20;
  // Weigh each face's pull by its current area (normalised by the sum of the areas) instead of
  // averaging the faces around a vertex uniformly.
  bool areaWeighted = false;
  // Boundary vertices stay where they are (otherwise they move like the others).
  bool fixedBoundary = false;
  FlipGuard flipGuard = FlipGuard::Input;
  // What "the input" of the guard is: empty, the mesh's face normals at the call; else one normal
  // per face (a denoiser running several passes gives the normals of its own input, so that no
  // face ends up flipped against the mesh it was given, however many passes). Single precision:
  // only the sign of a dot product with them is used, and a denoiser keeps two sets for a whole run.
  std::vector<Eigen::Vector3f> referenceNormals;
  // Threads of the per-face and per-vertex loops; results do not depend on them.
  ParallelOptions parallel;
  // For a caller that updates the same mesh many times (a denoiser's passes): the faces each vertex
  // gathers over, listed once by planVertexUpdate for this mesh and fixedBoundary. Used when every
  // face has a target (the lists are then the same as a call without it builds); else, or when
  // null, the lists are built for the call. Not owned.
  const VertexUpdatePlan* plan = nullptr;
};

// The faces each vertex's update gathers over when every face has a target: vertex v's are
// gatherFace[firstFace[v] .. firstFace[v + 1]), in the mesh's counter-clockwise order from its first
// half-edge; none for an isolated vertex, nor for a boundary vertex with fixedBoundary.
struct VertexUpdatePlan {
  int vertexCount = 0, faceCount = 0;
  bool fixedBoundary = false;
  std::vector<int> firstFace, gatherFace;
};

struct VertexUpdateResult {
  std::vector<Vec3> positions;  // one per mesh vertex
  int iterations = 0;           // iterations run
  int limitedSteps = 0;         // vertex steps the flip guard shortened, summed over iterations
  int frozenSteps = 0;          // of those, steps it cancelled entirely
  double maxDisplacement = 0;   // largest distance of a vertex from its input position
};

// Jacobi iterations of x_i += (1/|F_i|) Σ_{f∋i} n'_f (n'_f · (c_f − x_i)), with c_f the current
// centroid of face f and n'_f its (fixed) target normal.
//
// Flip guard: a candidate step is accepted only if every face keeps a positive projection of its
// normal on its input normal (a face never turns by 90° or more relative to the input) and on its
// current normal (no face turns by 90° or more within one iteration). The vertices of a face that
// breaks either rule have their step halved, and the check repeats on the faces around them; a
// vertex whose step was halved 8 times does not move this iteration. The current positions pass
// both checks, so the loop ends and the result never has a face flipped relative to the input.
// Faces of zero area in the input are exempt from the input check. With FlipGuard::InputOrTarget
// the input check also passes when the face lies on the positive side of its target normal, so a
// face the noise folded over may turn back; every face then ends facing its input or its target
// normal. Cost: the guard re-checks only the faces around shortened steps.
//
// The reference normals of the guard, in the single precision VertexUpdateOptions keeps them in.
std::vector<Eigen::Vector3f> referenceNormalsOf(const Mesh& mesh);

// Preconditions: targetNormals has one entry per face. Entries are normalised here; a zero vector
// means the face pulls on nothing. Throws InputError when the count is wrong, an entry is not
// finite (naming the face), iterations < 0 or options.plan was made for another mesh or
// fixedBoundary. Throws Cancelled through `progress`.
// targetNormals is taken by value: a caller done with its targets moves them in and they are
// normalised in place.
VertexUpdateResult updateVertices(const Mesh& mesh, std::vector<Vec3> targetNormals,
                                  const VertexUpdateOptions& options = {},
                                  const Progress& progress = {});

// The lists updateVertices builds for every call, built once (options: fixedBoundary and parallel).
VertexUpdatePlan planVertexUpdate(const Mesh& mesh, const VertexUpdateOptions& options = {});

// Face normals from filtered vertex normals: the normalised mean of each face's three vertex
// normals (the rule of the paper's §4.1). Where the three cancel out, the face's own geometric
// normal is used. Throws InputError when vertexNormals has not one entry per vertex or an entry
// is not finite (naming the vertex).
std::vector<Vec3> faceNormalsFromVertexNormals(const Mesh& mesh,
                                               const std::vector<Vec3>& vertexNormals);

}  // namespace geoshift

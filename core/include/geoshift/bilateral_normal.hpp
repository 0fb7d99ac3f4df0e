#pragma once
// Bilateral normal filtering (Zheng, Fu, Au, Tai, TVCG 2011, the local iterative scheme): a
// feature-preserving denoising baseline. Face normals are filtered with a spatial Gaussian on the
// distance between face centroids and a range Gaussian on the difference of the normals, then the
// vertices follow the filtered normals (vertex_update.hpp).
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/progress.hpp"
#include "geoshift/vertex_update.hpp"

namespace geoshift {

// Which faces a face's normal is averaged over (always including the face itself).
enum class FaceNeighborhood {
  Edge,    // the up to three faces sharing an edge
  Vertex,  // every face sharing at least one vertex (Zheng et al.'s usual choice)
};

struct BilateralNormalOptions {
  int normalIterations = 20;
  // σ_c in multiples of the average edge length; 0 means Zheng et al.'s default, the mean
  // distance between the centroids of edge-adjacent faces (about 0.58 AEL on a regular mesh).
  double sigmaSpatial = 0.0;
  // σ_s on |n_i − n_j| (unitless); 0.35 is the value most comparisons use.
  double sigmaRange = 0.35;
  FaceNeighborhood neighborhood = FaceNeighborhood::Vertex;
  VertexUpdateOptions vertexUpdate = {10, false, false, FlipGuard::Input, {}, {}};
};

struct BilateralNormalResult {
  std::vector<Vec3> faceNormals;  // the filtered normals the vertices were fitted to
  double sigmaSpatial = 0;        // σ_c used, in the mesh's units
  VertexUpdateResult vertexUpdate;  // its positions are moved into the mesh
};

// Filters the face normals of `mesh`, then moves its vertices to fit them (no face ends up flipped
// relative to the input: see updateVertices). On success the mesh's positions are replaced; when
// cancelled (Cancelled through `progress`) the mesh is left as it was.
// Throws InputError when normalIterations < 0, sigmaSpatial < 0, sigmaRange <= 0 (or either is not
// finite), or on bad vertex update options.
BilateralNormalResult bilateralNormalDenoise(Mesh& mesh, const BilateralNormalOptions& options = {},
                                             const Progress& progress = {});

// The normal filtering alone, on the given face normals (one per face), positions unchanged.
// sigmaSpatial here is absolute (mesh units, > 0). Same errors as above plus a count mismatch.
std::vector<Vec3> bilateralFilterFaceNormals(const Mesh& mesh, std::vector<Vec3> normals,
                                             double sigmaSpatial, const BilateralNormalOptions& options,
                                             const Progress& progress = {});

// Mean distance between the centroids of faces that share an edge (0 for a mesh without any).
double meanAdjacentCentroidDistance(const Mesh& mesh);

}  // namespace geoshift

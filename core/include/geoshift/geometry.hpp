#pragma once
// Basic differential quantities of a triangle mesh: lengths, normals, areas, bounds.
#include <vector>

#include <Eigen/Geometry>

#include "geoshift/mesh.hpp"

namespace geoshift {

// Mean length over all edges (each undirected edge once). The unit of every spatial parameter.
// Throws InputError for a mesh with no edge of positive length.
double averageEdgeLength(const Mesh& mesh);

// (b - a) × (c - a) for face f = (a, b, c): twice its area along its normal.
inline Vec3 faceCross(const Mesh& mesh, int f) {
  const Face& t = mesh.face(f);
  const Vec3& a = mesh.position(t[0]);
  return (mesh.position(t[1]) - a).cross(mesh.position(t[2]) - a);
}

// Unit normal per face (zero vector for a face of zero area).
std::vector<Vec3> faceNormals(const Mesh& mesh);
std::vector<double> faceAreas(const Mesh& mesh);

// The mean over interior edges of the angle (radians) between the normals of the two faces, with
// the mesh's faces at `positions` (one per vertex): the face normal field's total variation per
// edge. Noise adds to it; a crease adds about the same kept sharp or rounded over a few edges, and a
// curved part about the same smooth or in facets. A face of zero area has a zero normal (a right
// angle to any other). 0 for a mesh with no interior edge; InputError when the positions are not one
// per vertex.
double meanNormalTurn(const Mesh& mesh, const std::vector<Vec3>& positions);

// Angle-weighted vertex normals (Thürmer–Wüthrich); zero for isolated vertices.
std::vector<Vec3> vertexNormals(const Mesh& mesh);

// Mixed Voronoi areas (Meyer et al. 2003, as MeshLab: docs/algorithms.md#curvature); they sum to the total area.
std::vector<double> mixedVoronoiAreas(const Mesh& mesh);

// Axis-aligned bounds of the positions (empty box for none).
Eigen::AlignedBox3d boundingBox(const std::vector<Vec3>& positions);

// Uniform scale and translation that maps the bounding box into the unit cube [0,1]^3 (longest side 1,
// centred); apply with normalized = scale * p + offset.
struct Similarity {
  double scale = 1.0;
  Vec3 offset = Vec3::Zero();
  Vec3 apply(const Vec3& p) const { return scale * p + offset; }
};
Similarity unitCubeTransform(const std::vector<Vec3>& positions);
// Applies unitCubeTransform in place and returns it.
Similarity normalizeToUnitCube(Mesh& mesh);

}  // namespace geoshift

#pragma once
// Geodesics on a triangle mesh: points on the surface, tangent frames, the log map by discrete
// geodesic polar coordinates (Melvær–Reimers 2012; docs/algorithms.md#log-map) and the exp map by straightest
// geodesics (Polthier–Schmies 1998; docs/algorithms.md#exp-map).
//
// Tangent vectors are 2D coordinates in the frame of their base point, the same for log and exp:
//  - at a vertex v: geodesic polar coordinates around v. Angle 0 lies along halfedge(v) (for a
//    boundary vertex, the boundary edge); each further outgoing edge, counter-clockwise, lies at the
//    cumulative corner angle scaled by 2π/θ(v) at an interior vertex (cone normalisation, θ(v) =
//    sum of corner angles), unscaled at a boundary vertex, where angles run over [0, θ(v)].
//  - anywhere else (inside a face or on an edge): the frame of the point's face, x along the face's
//    first edge face[0] -> face[1], y = n × x, n the face's unit normal.
// A point is at a vertex when one of its barycentric coordinates is at least 1 - kVertexSnap.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "geoshift/mesh.hpp"

namespace geoshift {

using Vec2 = Eigen::Vector2d;

inline constexpr double kVertexSnap = 1e-9;

struct SurfacePoint {
  int face = -1;
  Vec3 bary = Vec3::Constant(1.0 / 3.0);  // weights of face[0], face[1], face[2]; they sum to 1

  // The corner of a face at v (the face of halfedge(v)). Throws InputError for an isolated vertex.
  static SurfacePoint atVertex(const Mesh& mesh, int v);
  // The point tail(h) + t (head(h) - tail(h)) in face(h), t in [0, 1].
  static SurfacePoint onEdge(const Mesh& mesh, int halfedge, double t);
  // Throws InputError naming the face when it is out of range or the coordinates are not finite,
  // negative beyond round-off, or do not sum to 1 (they are renormalised within 1e-6).
  static SurfacePoint inFace(const Mesh& mesh, int face, const Vec3& bary);

  Vec3 position(const Mesh& mesh) const;
  // The vertex the point sits on (kVertexSnap), or -1.
  int vertex(const Mesh& mesh) const;
};

// Intrinsic quantities that the log and exp maps share, computed once for a mesh's geometry.
// Keeps a reference to the mesh: the mesh must outlive it and keep its positions.
class SurfaceGeometry {
 public:
  explicit SurfaceGeometry(const Mesh& mesh);

  const Mesh& mesh() const { return mesh_; }
  double averageEdgeLength() const { return averageEdgeLength_; }
  double length(int h) const { return length_[h]; }            // |head(h) - tail(h)|
  double cornerAngle(int h) const { return cornerAngle_[h]; }  // angle of face(h) at tail(h)
  double angleSum(int v) const { return angleSum_[v]; }        // θ(v)
  // 2π/θ(v) at an interior vertex, 1 at a boundary vertex (and an isolated one).
  double angleScale(int v) const { return angleScale_[v]; }
  // The polar angle of outgoing half-edge h in the vertex frame of tail(h), in [0, 2π) inside,
  // in [0, θ] on the boundary.
  double polarAngle(int h) const { return polarAngle_[h]; }
  const Vec3& faceNormal(int f) const { return faceNormal_[f]; }
  const Vec3& faceAxis(int f) const { return faceAxis_[f]; }  // unit x axis of the face frame

  // A 3D vector in face f's plane as 2D coordinates of the face frame, and back.
  Vec2 toFaceFrame(int f, const Vec3& v) const;
  Vec3 fromFaceFrame(int f, const Vec2& v) const;

 private:
  const Mesh& mesh_;
  double averageEdgeLength_ = 0;
  std::vector<double> length_, cornerAngle_, angleSum_, angleScale_, polarAngle_;
  std::vector<Vec3> faceNormal_, faceAxis_;
};

// ---------------------------------------------------------------------------------------------
// Log map (DGPC)

struct LogMapEntry {
  int vertex;
  double distance;  // U, geodesic distance from the source
  double angle;     // Θ, polar angle in the source's frame
  Vec2 coords() const;  // U (cos Θ, sin Θ)
};

// Reusable solver: keeps its buffers between calls and resets only what a call touched, so one call
// costs O(k log k) in the k vertices it reaches, not O(n).
class LogMap {
 public:
  explicit LogMap(const SurfaceGeometry& geometry);
  // A second solver on the same geometry that shares this one's read-only tables (each vertex's
  // ring of neighbours and faces, 320 bytes a vertex) and has its own buffers (16 bytes a vertex):
  // one per thread. Solvers must not be shared between threads; forks may run concurrently.
  LogMap fork() const;
  // Polar coordinates of every vertex within `radius` (absolute units) of the source, in order of
  // increasing distance; the source vertex itself (if any) first with distance 0. Valid until the
  // next call. Throws InputError for a bad source point or radius <= 0.
  const std::vector<LogMapEntry>& compute(const SurfacePoint& source, double radius);
  const std::vector<LogMapEntry>& computeFromVertex(int vertex, double radius);

 private:
  struct Tables;
  struct State;
  LogMap(const SurfaceGeometry& geometry, std::shared_ptr<const Tables> tables);
  const SurfaceGeometry& geometry_;
  std::shared_ptr<const Tables> tables_;
  std::shared_ptr<State> state_;
};

// One-shot convenience (builds the geometry; prefer LogMap for repeated calls).
std::vector<LogMapEntry> logMap(const Mesh& mesh, const SurfacePoint& source, double radius);

// ---------------------------------------------------------------------------------------------
// Exp map (straightest geodesics)

struct ExpMapOptions {
  bool recordPath = false;  // keep the 3D polyline of the trace
};

struct ExpMapResult {
  SurfacePoint end;
  bool hitBoundary = false;  // stopped early at a boundary edge or vertex; `end` is on it
  double length = 0;         // length traced (the vector's length unless hitBoundary)
  int facesCrossed = 0;
  std::vector<Vec3> path;    // with recordPath: start, every edge/vertex crossing, end
};

// Walks the tangent vector (in the start point's frame) along a straightest geodesic: straight
// inside faces, unfolded across edges, leaving a vertex with equal angle sums left and right.
// Stops at the boundary (hitBoundary); from a boundary vertex, a polar angle outside [0, θ(v)]
// points off the surface and returns the start. Throws InputError for a face out of range or a
// non-finite vector.
ExpMapResult expMap(const SurfaceGeometry& geometry, const SurfacePoint& start, const Vec2& vector,
                    const ExpMapOptions& options = {});

// A 3D direction at the point as a tangent vector of the point's frame, with the same length after
// projection onto the tangent plane (the face's plane; at a vertex, the plane of the face of the
// point, whose wedge fixes the polar angle). Returns zero for a direction normal to the plane.
Vec2 tangentFromDirection(const SurfaceGeometry& geometry, const SurfacePoint& point, const Vec3& direction);

}  // namespace geoshift

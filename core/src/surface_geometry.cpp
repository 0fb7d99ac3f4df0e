// Surface points and the intrinsic quantities shared by the log and exp maps (geodesic.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift {

SurfacePoint SurfacePoint::atVertex(const Mesh& mesh, int v) {
  if (v < 0 || v >= mesh.vertexCount())
    throw InputError("vertex " + std::to_string(v) + " is out of range (" + std::to_string(mesh.vertexCount()) +
                     " vertices)");
  const int h = mesh.halfedge(v);
  if (h < 0) throw InputError("vertex " + std::to_string(v) + " is isolated: no face touches it");
  SurfacePoint p;
  p.face = Mesh::faceOf(h);
  p.bary = Vec3::Zero();
  p.bary[h % 3] = 1.0;
  return p;
}

SurfacePoint SurfacePoint::onEdge(const Mesh& mesh, int h, double t) {
  if (h < 0 || h >= mesh.halfedgeCount())
    throw InputError("half-edge " + std::to_string(h) + " is out of range");
  t = std::clamp(t, 0.0, 1.0);
  SurfacePoint p;
  p.face = Mesh::faceOf(h);
  p.bary = Vec3::Zero();
  p.bary[h % 3] = 1.0 - t;
  p.bary[(h % 3 + 1) % 3] = t;
  return p;
}

SurfacePoint SurfacePoint::inFace(const Mesh& mesh, int face, const Vec3& bary) {
  if (face < 0 || face >= mesh.faceCount()) {
    std::ostringstream s;
    s << "face " << face << " is out of range (" << mesh.faceCount() << " faces)";
    throw InputError(s.str());
  }
  const double sum = bary.sum();
  if (!bary.allFinite() || bary.minCoeff() < -1e-6 || std::abs(sum - 1.0) > 1e-6) {
    std::ostringstream s;
    s << "barycentric coordinates (" << bary.x() << ", " << bary.y() << ", " << bary.z() << ") on face " << face
      << " must be non-negative and sum to 1";
    throw InputError(s.str());
  }
  SurfacePoint p;
  p.face = face;
  p.bary = bary.cwiseMax(0.0) / bary.cwiseMax(0.0).sum();
  return p;
}

Vec3 SurfacePoint::position(const Mesh& mesh) const {
  const Face& f = mesh.face(face);
  return bary[0] * mesh.position(f[0]) + bary[1] * mesh.position(f[1]) + bary[2] * mesh.position(f[2]);
}

int SurfacePoint::vertex(const Mesh& mesh) const {
  for (int k = 0; k < 3; ++k)
    if (bary[k] >= 1.0 - kVertexSnap) return mesh.face(face)[k];
  return -1;
}

SurfaceGeometry::SurfaceGeometry(const Mesh& mesh) : mesh_(mesh) {
  const int nh = mesh.halfedgeCount(), nv = mesh.vertexCount(), nf = mesh.faceCount();
  length_.resize(nh);
  cornerAngle_.resize(nh);
  for (int h = 0; h < nh; ++h) {
    const Vec3 a = mesh.position(mesh.head(h)) - mesh.position(mesh.tail(h));
    const Vec3 b = mesh.position(mesh.tail(Mesh::prev(h))) - mesh.position(mesh.tail(h));
    length_[h] = a.norm();
    // atan2 of |a×b| and a·b stays accurate for needle corners, where acos of a cosine does not.
    cornerAngle_[h] = std::atan2(a.cross(b).norm(), a.dot(b));
  }
  faceNormal_.resize(nf);
  faceAxis_.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const Face& t = mesh.face(f);
    faceNormal_[f] = faceCross(mesh, f).normalized();
    faceAxis_[f] = (mesh.position(t[1]) - mesh.position(t[0])).normalized();
  }
  angleSum_.assign(nv, 0.0);
  angleScale_.assign(nv, 1.0);
  polarAngle_.assign(nh, 0.0);
  for (int v = 0; v < nv; ++v) {
    double sum = 0;
    mesh.forEachOutgoing(v, [&](int h) {
      polarAngle_[h] = sum;
      sum += cornerAngle_[h];
    });
    angleSum_[v] = sum;
    if (!mesh.isIsolated(v) && !mesh.isBoundaryVertex(v) && sum > 0) {
      angleScale_[v] = 2 * std::numbers::pi / sum;
      mesh.forEachOutgoing(v, [&](int h) { polarAngle_[h] *= angleScale_[v]; });
    }
  }
  averageEdgeLength_ = geoshift::averageEdgeLength(mesh);
}

Vec2 SurfaceGeometry::toFaceFrame(int f, const Vec3& v) const {
  const Vec3& x = faceAxis_[f];
  const Vec3 y = faceNormal_[f].cross(x);
  return {v.dot(x), v.dot(y)};
}

Vec3 SurfaceGeometry::fromFaceFrame(int f, const Vec2& v) const {
  const Vec3& x = faceAxis_[f];
  return v.x() * x + v.y() * faceNormal_[f].cross(x);
}

Vec2 LogMapEntry::coords() const { return distance * Vec2(std::cos(angle), std::sin(angle)); }

}  // namespace geoshift

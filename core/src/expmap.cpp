// Exp map by straightest geodesics (Polthier–Schmies 1998; docs/algorithms.md#exp-map) and the conversion of
// 3D directions into the tangent frames of geodesic.hpp.
//
// The trace keeps its position as barycentric coordinates of the current face and what is left
// of the vector as a 2D displacement in that face's layout (the face frame scaled by the length of
// the face's first edge, which spares a square root and a division per face). Crossing an edge
// re-expresses the displacement relative to the shared edge, which is what unfolding the next
// face into the plane amounts to: no face is laid out next to another, no 3D rotation is needed,
// and the change of scale between the two layouts comes out of the edge ratio by itself.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"

namespace geoshift {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
// A crossing whose edge parameter is this close to an end goes through the vertex
// (docs/algorithms.md#exp-map): snapping there lets the path leave with θ(v)/2 on either side instead of being nudged
// into whichever face round-off picks.
constexpr double kVertexHit = 1e-9;
// Least component of the unit direction into a face just entered (docs/algorithms.md#exp-map). A grazing
// direction, along the entry edge or by round-off pointing back out, would otherwise run along
// that edge, or outside the face with the opposite corner's coordinate going negative.
constexpr double kMinInward = 1e-9;
// Normalised angles this far beyond [0, θ] at a boundary vertex are round-off of a direction along
// one of its boundary edges, not a direction off the surface.
constexpr double kBoundaryAngleSlack = 1e-9;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 perp(const Vec2& a) { return {-a.y(), a.x()}; }
Vec3 unitBary(int corner) {
  Vec3 b = Vec3::Zero();
  b[corner] = 1.0;
  return b;
}
// Round-off can leave a coordinate at -1e-17 after a step; the contract wants them valid.
Vec3 cleanBary(const Vec3& b) {
  const Vec3 c = b.cwiseMax(0.0);
  const double s = c.sum();
  return s > 0 ? Vec3(c / s) : Vec3::Constant(1.0 / 3.0);
}
double wrapAngle(double phi) {
  phi = std::fmod(phi, kTwoPi);
  if (phi < 0) phi += kTwoPi;
  return phi >= kTwoPi ? 0.0 : phi;
}

// A face in its own frame scaled by s = |e1| (e1 = face[0] -> face[1]): corner 1 at (s², 0),
// corner 2 at (e1·e2, |e1 × e2|), the same orientation as SurfaceGeometry's toFaceFrame. Built from
// the positions rather than the stored axis and normal, which would cost two more cache lines per
// face on large meshes. Barycentric rates and edge-relative angles do not depend on the scale.
struct Layout {
  Vec2 p[3];
  double twiceArea = 0;  // in the scaled layout: s² 2A
  double scale() const { return std::sqrt(p[1].x()); }
  Vec2 edge(int k) const { return p[(k + 1) % 3] - p[k]; }  // half-edge 3f + k
};

Layout layoutOf(const Mesh& mesh, int f) {
  const Face& t = mesh.face(f);
  const Vec3& o = mesh.position(t[0]);
  const Vec3 e1 = mesh.position(t[1]) - o;
  const Vec3 e2 = mesh.position(t[2]) - o;
  Layout L;
  L.p[0] = Vec2::Zero();
  L.p[1] = Vec2(e1.squaredNorm(), 0.0);
  L.p[2] = Vec2(e1.dot(e2), e1.cross(e2).norm());
  L.twiceArea = L.p[1].x() * L.p[2].y();
  return L;
}

class Tracer {
 public:
  Tracer(const SurfaceGeometry& geometry, const ExpMapOptions& options, ExpMapResult& result, double total)
      : g_(geometry), mesh_(geometry.mesh()), options_(options), r_(result), total_(total) {}

  // Starts inside face `face` (or on one of its edges) along `vector` (face frame, true length).
  void startInFace(int face, const Vec3& bary, const Vec2& vector) {
    face_ = face;
    layout_ = layoutOf(mesh_, face);
    bary_ = cleanBary(bary);
    disp_ = layout_.scale() * vector;
    blocked_ = 0;
  }

  // Starts at v in the direction of normalised polar angle phi; false when the direction leaves
  // the surface (a boundary vertex, phi outside [0, θ]).
  bool startAtVertex(int v, double phi) { return leaveVertex(v, phi); }

  void run() {
    const long maxSteps = 10L * mesh_.faceCount() + 1000;
    for (long step = 0; step < maxSteps && !done_; ++step) advance();
    r_.end.face = face_;
    r_.end.bary = cleanBary(bary_);
    r_.length = traced_;
    if (options_.recordPath) record(r_.end.position(mesh_));
  }

 private:
  // One straight piece inside the current face: to the end of the displacement, to the edge it
  // leaves by, or to the vertex it passes through.
  void advance() {
    prefetchNeighbours();
    const Layout& L = layout_;
    // Over the whole displacement D, 2A λ_i changes by cross(e_i, D), e_i the edge opposite i.
    // The first coordinate to reach zero, at fraction b_i 2A / -rate_i < 1, names the exit edge;
    // fractions are compared cross-multiplied so that only the winner costs a division.
    double rate[3];
    int exit = -1;
    double tExit = 1;
    for (int i = 0; i < 3; ++i) {
      rate[i] = cross2(L.p[(i + 2) % 3] - L.p[(i + 1) % 3], disp_);
      if ((blocked_ >> i & 1) || !(rate[i] < 0)) continue;
      const double num = bary_[i] * L.twiceArea;
      if (num < -rate[i] * tExit) tExit = num / -rate[i], exit = i;
    }
    const Vec3 rates(rate[0], rate[1], rate[2]);
    if (exit < 0) {
      // Stays inside (or, round-off having blocked every exit, stops where it is: no NaN from a
      // division by a vanishing area).
      if (L.twiceArea > 0) bary_ = cleanBary(bary_ + rates / L.twiceArea);
      traced_ += remaining_;
      remaining_ = 0;
      done_ = true;
      return;
    }
    Vec3 b = L.twiceArea > 0 ? Vec3(bary_ + (tExit / L.twiceArea) * rates) : bary_;
    b[exit] = 0;
    b = b.cwiseMax(0.0);
    traced_ += tExit * remaining_;
    remaining_ -= tExit * remaining_;
    disp_ *= 1 - tExit;

    const int a = (exit + 1) % 3, c = (exit + 2) % 3;  // the edge runs from corner a to corner c
    const double sum = b[a] + b[c];
    const double t = sum > 0 ? b[c] / sum : 0.5;
    bary_ = Vec3::Zero();
    bary_[a] = 1 - t;
    bary_[c] = t;
    if (nearlyDone()) {
      done_ = true;
      return;
    }
    const Vec2 e = L.edge(a);
    const double ee = e.squaredNorm();
    // A zero-length edge has no direction to measure against; its ends coincide, so it is a vertex.
    if (t < kVertexHit || t > 1 - kVertexHit || !(ee > 0)) {
      passVertex(t < 0.5 ? a : c);
      return;
    }
    if (options_.recordPath) record(SurfacePoint{face_, bary_}.position(mesh_));
    const int h = 3 * face_ + a, ht = mesh_.twin(h);
    if (ht < 0) {
      stopHere(true);
      return;
    }
    // D = α e + β' perp(e) with β' < 0 (leaving). The twin runs the other way, so in its face the
    // same line is e' = -e and "out of the old face" is "into the new one": D' = -α e' + β perp(e'),
    // β = -β'. The ratio |e'| / |e| carries the change of layout scale.
    double along = disp_.dot(e) / ee, inward = -cross2(e, disp_) / ee;
    if (!(inward > 0) || inward * inward < kMinInward * kMinInward * (along * along + inward * inward)) {
      const double n = std::hypot(along, inward);
      inward = kMinInward * n;
      along = std::copysign(std::sqrt(std::max(0.0, n * n - inward * inward)), along);
    }
    const int k = ht % 3;
    face_ = Mesh::faceOf(ht);
    layout_ = layoutOf(mesh_, face_);
    const Vec2 ep = layout_.edge(k);
    disp_ = -along * ep + inward * perp(ep);
    bary_ = Vec3::Zero();
    bary_[k] = t;  // tail(ht) = head(h), which carries weight t
    bary_[(k + 1) % 3] = 1 - t;
    blocked_ = 1 << ((k + 2) % 3);
    ++r_.facesCrossed;
  }

  // The path reached the vertex at `corner` of the current face: leave so that both sides get
  // θ(v)/2 (Polthier–Schmies), which at normalised angles is the incoming direction turned by π.
  void passVertex(int corner) {
    const int v = mesh_.face(face_)[corner];
    bary_ = unitBary(corner);
    record(mesh_.position(v));
    if (mesh_.isBoundaryVertex(v)) {
      stopHere(true);
      return;
    }
    const int h = 3 * face_ + corner;
    const Vec2 e = layout_.edge(corner);
    const Vec2 back = -disp_;
    // The way back lies in this face's wedge at v; round-off may put it a hair outside.
    const double beta = std::clamp(std::atan2(cross2(e, back), e.dot(back)), 0.0, g_.cornerAngle(h));
    const double phiBack = g_.polarAngle(h) + beta * g_.angleScale(v);
    const int before = face_;
    if (!leaveVertex(v, wrapAngle(phiBack + kPi))) stopHere(true);
    if (face_ != before) ++r_.facesCrossed;
  }

  // Sets the state to leave v at normalised angle phi into the wedge that contains it.
  bool leaveVertex(int v, double phi) {
    if (mesh_.isBoundaryVertex(v)) {
      const double theta = g_.angleSum(v);
      if (phi > theta) {
        if (phi - theta <= kBoundaryAngleSlack)
          phi = theta;
        else if (kTwoPi - phi <= kBoundaryAngleSlack)
          phi = 0;
        else
          return false;
      }
    }
    int wedge = mesh_.halfedge(v);
    mesh_.forEachOutgoing(v, [&](int h) {
      if (g_.polarAngle(h) <= phi) wedge = h;
    });
    const double beta =
        std::clamp((phi - g_.polarAngle(wedge)) / g_.angleScale(v), 0.0, g_.cornerAngle(wedge));
    const int corner = wedge % 3;
    const Layout L = layoutOf(mesh_, Mesh::faceOf(wedge));
    const Vec2 e = L.edge(corner);
    const double len = e.norm();
    if (!(len > 0)) return false;
    face_ = Mesh::faceOf(wedge);
    layout_ = L;
    disp_ = (remaining_ * L.scale() / len) * (std::cos(beta) * e + std::sin(beta) * perp(e));
    bary_ = unitBary(corner);
    // Only the edge opposite v may end this piece: the edges at v would give a zero-length exit
    // back into the vertex whenever round-off tilts the direction out of the wedge.
    blocked_ = 7 & ~(1 << corner);
    return true;
  }

  // On a large mesh each face entered costs a chain of three cache misses (twin, the face's
  // corners, the new corner's position) that dominates the arithmetic. Starting the chains of
  // both possible exits now lets them overlap with the work on the current face.
  void prefetchNeighbours() const {
#if defined(__GNUC__) || defined(__clang__)
    for (int i = 0; i < 3; ++i) {
      if (blocked_ >> i & 1) continue;
      const int ht = mesh_.twin(3 * face_ + (i + 1) % 3);
      if (ht < 0) continue;
      const Face& t = mesh_.face(Mesh::faceOf(ht));
      __builtin_prefetch(&mesh_.position(t[(ht % 3 + 2) % 3]));
    }
#endif
  }

  void stopHere(bool atBoundary) {
    done_ = true;
    r_.hitBoundary = atBoundary;
  }
  bool nearlyDone() const { return remaining_ <= 1e-12 * total_; }
  void record(const Vec3& p) {
    if (options_.recordPath) r_.path.push_back(p);
  }

  const SurfaceGeometry& g_;
  const Mesh& mesh_;
  const ExpMapOptions& options_;
  ExpMapResult& r_;
  const double total_;
  double remaining_ = total_;  // true length still to go
  double traced_ = 0;
  bool done_ = false;
  int face_ = -1;
  Layout layout_;
  Vec3 bary_ = Vec3::Zero();
  Vec2 disp_ = Vec2::Zero();  // what is left of the vector, in the current face's scaled layout
  int blocked_ = 0;           // bit i: the edge opposite corner i cannot be left by (the entry edge)
};

void checkPoint(const Mesh& mesh, const SurfacePoint& p, const char* what) {
  if (p.face < 0 || p.face >= mesh.faceCount())
    throw InputError(std::string(what) + ": face " + std::to_string(p.face) + " is out of range (" +
                     std::to_string(mesh.faceCount()) + " faces)");
  if (!p.bary.allFinite())
    throw InputError(std::string(what) + ": barycentric coordinates on face " + std::to_string(p.face) +
                     " are not finite");
}

}  // namespace

// Throws InputError for a start face out of range, non-finite barycentrics or a non-finite vector.
// At a boundary vertex a direction whose normalised angle lies outside [0, θ(v)] points off the
// surface: the result is the start point, length 0, hitBoundary. Stops after 10 F + 1000 pieces
// (only reachable on degenerate geometry), returning the point reached.
ExpMapResult expMap(const SurfaceGeometry& geometry, const SurfacePoint& start, const Vec2& vector,
                    const ExpMapOptions& options) {
  const Mesh& mesh = geometry.mesh();
  checkPoint(mesh, start, "exp map start");
  if (!vector.allFinite()) throw InputError("exp map: the tangent vector is not finite");
  ExpMapResult result;
  result.end = start;
  result.end.bary = cleanBary(start.bary);
  const double length = vector.norm();
  if (options.recordPath) result.path.push_back(result.end.position(mesh));
  if (!(length > 0)) {
    if (options.recordPath) result.path.push_back(result.end.position(mesh));
    return result;
  }
  Tracer tracer(geometry, options, result, length);
  if (const int v = start.vertex(mesh); v >= 0) {
    if (!tracer.startAtVertex(v, wrapAngle(std::atan2(vector.y(), vector.x())))) {
      if (options.recordPath) result.path.push_back(result.end.position(mesh));
      result.hitBoundary = true;
      return result;
    }
  } else {
    tracer.startInFace(start.face, start.bary, vector);
  }
  tracer.run();
  return result;
}

// At a vertex the angle is measured in the plane of the point's face from the outgoing half-edge of
// its corner there, then scaled by angleScale(v) and offset by that half-edge's polar angle. A
// direction outside the corner's wedge still gets an angle (negative or beyond the corner, wrapped
// to [0, 2π)): it is the wedge's own extrapolation, not the angle of the wedge the direction
// actually points into. At a boundary vertex such an angle may fall outside [0, θ(v)], and expMap
// then treats the vector as pointing off the surface.
Vec2 tangentFromDirection(const SurfaceGeometry& geometry, const SurfacePoint& point, const Vec3& direction) {
  const Mesh& mesh = geometry.mesh();
  checkPoint(mesh, point, "tangent direction");
  if (!direction.allFinite()) throw InputError("tangent direction: the 3D direction is not finite");
  const int f = point.face;
  const Vec3& n = geometry.faceNormal(f);
  const Vec2 d = geometry.toFaceFrame(f, direction - direction.dot(n) * n);
  const double length = d.norm();
  if (!(length > 0)) return Vec2::Zero();
  const int v = point.vertex(mesh);
  if (v < 0) return d;
  int corner = 0;
  while (mesh.face(f)[corner] != v) ++corner;
  const int h = 3 * f + corner;
  const Vec2 e = geometry.toFaceFrame(f, mesh.position(mesh.head(h)) - mesh.position(v));
  const double beta = std::atan2(cross2(e, d), e.dot(d));
  const double phi = wrapAngle(geometry.polarAngle(h) + beta * geometry.angleScale(v));
  return length * Vec2(std::cos(phi), std::sin(phi));
}

}  // namespace geoshift

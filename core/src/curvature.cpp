#include "geoshift/curvature.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "geoshift/geometry.hpp"

namespace geoshift {
namespace {

double angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// The other boundary neighbour of boundary vertex v: halfedge(v) leaves v along the boundary, and
// the last outgoing half-edge of the counter-clockwise fan is preceded by the incoming boundary one.
int incomingBoundaryNeighbor(const Mesh& mesh, int v) {
  int last = -1;
  mesh.forEachOutgoing(v, [&](int h) { last = h; });
  return mesh.tail(Mesh::prev(last));
}

}  // namespace

double Curvatures::absolute(int v) const {
  const double h = mean[v], k = gaussian[v];
  // |k1| + |k2|: with k1 k2 >= 0 both have the sign of H; otherwise it is k1 - k2 = 2 sqrt(H² - K).
  return k >= 0 ? std::abs(2.0 * h) : 2.0 * std::sqrt(std::abs(h * h - k));
}

double Curvatures::rms(int v) const {
  const double h = mean[v], k = gaussian[v];
  return std::sqrt(std::abs(4.0 * h * h - 2.0 * k));  // sqrt(k1² + k2²)
}

std::vector<double> Curvatures::get(CurvatureKind kind) const {
  switch (kind) {
    case CurvatureKind::Mean: return mean;
    case CurvatureKind::Gaussian: return gaussian;
    case CurvatureKind::Absolute:
    case CurvatureKind::Rms: {
      std::vector<double> out(mean.size());
      for (size_t v = 0; v < out.size(); ++v) {
        out[v] = kind == CurvatureKind::Absolute ? absolute(static_cast<int>(v))
                                                 : rms(static_cast<int>(v));
      }
      return out;
    }
  }
  return {};
}

Curvatures curvatures(const Mesh& mesh) {
  // vcglib UpdateCurvature::MeanAndGaussian (Meyer et al. 2003), in double instead of float.
  const int n = mesh.vertexCount();
  Curvatures c;
  c.area = mixedVoronoiAreas(mesh);
  c.mean.assign(n, 0.0);
  c.gaussian.assign(n, 0.0);
  const std::vector<Vec3> normals = vertexNormals(mesh);

  // C_v = ¼ Σ cot(opposite angle)(x_v − x_j) = (A/2) K_Meyer with K_Meyer = 2H n (Meyer eq. 8).
  std::vector<Vec3> meanVector(n, Vec3::Zero());
  std::vector<double> angleSum(n, 0.0);
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const Face& t = mesh.face(f);
    const std::array<Vec3, 3> p = {mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2])};
    const double doubleArea = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(doubleArea > 0)) continue;  // vcglib skips faces with a zero angle
    std::array<double, 3> angle, cot;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      angle[k] = angleBetween(a, b);
      cot[k] = a.dot(b) / doubleArea;
    }
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      // Edge (k, k1) is opposite corner k2, edge (k, k2) opposite corner k1.
      meanVector[t[k]] += (cot[k2] * (p[k] - p[k1]) + cot[k1] * (p[k] - p[k2])) / 4.0;
      angleSum[t[k]] += angle[k];
    }
  }

  for (int v = 0; v < n; ++v) {
    const double area = c.area[v];
    if (mesh.isIsolated(v) || !(area > 0)) continue;
    double deficit = 2.0 * std::numbers::pi - angleSum[v];
    if (mesh.isBoundaryVertex(v)) {
      // vcglib's boundary correction: also subtract the angle between the two boundary edges, so
      // that a vertex on a straight border of a flat region gets K = 0 (a convex corner of angle
      // β still gets 2π − 2β: π/A at a square corner, as in MeshLab).
      const Vec3& x = mesh.position(v);
      const Vec3 e1 = mesh.position(mesh.head(mesh.halfedge(v))) - x;
      const Vec3 e2 = mesh.position(incomingBoundaryNeighbor(mesh, v)) - x;
      deficit -= angleBetween(e1, e2);
      // Deviation from vcglib: at a border the cotangent sum also holds the in-plane gradient of
      // the area (the open border pulls the vertex outward), which vcglib's |C| turns into a spike
      // of about 1/edge length on a flat border. Only the normal part is curvature.
      c.mean[v] = meanVector[v].dot(normals[v]) / area;
    } else {
      const double sign = meanVector[v].dot(normals[v]) > 0 ? 1.0 : -1.0;
      c.mean[v] = sign * meanVector[v].norm() / area;
    }
    c.gaussian[v] = deficit / area;
  }
  return c;
}

std::vector<double> colorMap(const std::vector<double>& values) {
  std::vector<double> rgb(values.size() * 3, 0.0);
  if (values.empty()) return rgb;
  // MeshLab clamps the colour ramp at the 10% and 90% percentiles so that a few spikes (needles,
  // borders) do not squash every other value into one colour.
  std::vector<double> sorted;
  sorted.reserve(values.size());
  for (double x : values) {
    if (std::isfinite(x)) sorted.push_back(x);
  }
  if (sorted.empty()) return rgb;
  std::sort(sorted.begin(), sorted.end());
  auto percentile = [&](double q) {
    return sorted[static_cast<size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5)];
  };
  const double lo = percentile(0.10), hi = percentile(0.90);
  auto lerp = [](const std::array<double, 3>& a, const std::array<double, 3>& b, double t) {
    return std::array<double, 3>{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]),
                                 a[2] + t * (b[2] - a[2])};
  };
  const bool diverging = lo < 0 && hi > 0;
  // Diverging: zero stays white whatever the skew, so the sign of (say) mean curvature reads directly.
  const double scale = diverging ? std::max(-lo, hi) : hi - lo;
  const std::array<std::array<double, 3>, 5> ramp = {{{0.267, 0.005, 0.329},
                                                      {0.230, 0.322, 0.546},
                                                      {0.128, 0.567, 0.551},
                                                      {0.369, 0.789, 0.383},
                                                      {0.993, 0.906, 0.144}}};  // viridis stops
  for (size_t i = 0; i < values.size(); ++i) {
    const double x = std::isfinite(values[i]) ? values[i] : 0.0;
    std::array<double, 3> color;
    if (diverging) {
      const double t = std::clamp(x / scale, -1.0, 1.0);
      color = t < 0 ? lerp({1, 1, 1}, {0.23, 0.30, 0.75}, -t) : lerp({1, 1, 1}, {0.71, 0.02, 0.15}, t);
    } else {
      const double t = scale > 0 ? std::clamp((x - lo) / scale, 0.0, 1.0) : 0.5;
      const double s = t * 4.0;
      const int k = std::min(3, static_cast<int>(s));
      color = lerp(ramp[k], ramp[k + 1], s - k);
    }
    for (int j = 0; j < 3; ++j) rgb[3 * i + j] = color[j];
  }
  return rgb;
}

}  // namespace geoshift

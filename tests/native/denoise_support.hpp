#pragma once
// Shared by the denoiser tests: noisy copies, distances to the clean surface, crease errors, flips.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "geoshift/geometry.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/noise.hpp"

namespace geoshift::test {

inline Mesh withNoise(const Mesh& clean, double amount, std::uint64_t seed = 1,
                      NoiseDistribution distribution = NoiseDistribution::Fixed) {
  Mesh m = clean;
  NoiseOptions o;
  o.amount = amount;
  o.distribution = distribution;
  o.seed = seed;
  addNoise(m, o);
  return m;
}

inline double rmsTo(const Mesh& result, const Mesh& clean) { return pointToSurface(result.positions(), clean).rms; }

inline double degrees(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

// For every edge where the clean mesh bends by more than 30°: |dihedral(result) − dihedral(clean)|.
inline std::vector<double> featureEdgeErrors(const Mesh& clean, const Mesh& result) {
  const std::vector<Vec3> nc = faceNormals(clean), nr = faceNormals(result);
  std::vector<double> errors;
  for (int h = 0; h < clean.halfedgeCount(); ++h) {
    const int t = clean.twin(h);
    if (t <= h) continue;
    const int f = Mesh::faceOf(h), g = Mesh::faceOf(t);
    const double bend = degrees(nc[f], nc[g]);
    if (bend > 30) errors.push_back(std::abs(degrees(nr[f], nr[g]) - bend));
  }
  return errors;
}

inline double meanFeatureEdgeError(const Mesh& clean, const Mesh& result) {
  const std::vector<double> e = featureEdgeErrors(clean, result);
  return e.empty() ? 0 : std::accumulate(e.begin(), e.end(), 0.0) / e.size();
}

// Faces whose normal turned by 90° or more between the two meshes.
inline int flippedFaces(const Mesh& before, const Mesh& after) {
  const std::vector<Vec3> a = faceNormals(before), b = faceNormals(after);
  int flipped = 0;
  for (size_t f = 0; f < a.size(); ++f)
    if (a[f].dot(b[f]) <= 0) ++flipped;
  return flipped;
}

}  // namespace geoshift::test

#pragma once
// Discrete curvatures as MeshLab's "Discrete Curvatures" filter computes them (docs/algorithms.md#curvature).
#include <vector>

#include "geoshift/mesh.hpp"

namespace geoshift {

enum class CurvatureKind { Mean, Gaussian, Absolute, Rms };

struct Curvatures {
  std::vector<double> mean;      // H = (k1 + k2) / 2, positive on a sphere with outward normals
  std::vector<double> gaussian;  // K = (2π - Σ angles) / A (boundary: minus the boundary angle too)
  std::vector<double> area;      // mixed Voronoi area A
  // |k1| + |k2|: |2H| if K >= 0, else 2 sqrt(|H² - K|).
  double absolute(int v) const;
  double rms(int v) const;        // sqrt(|4H² - 2K|)
  std::vector<double> get(CurvatureKind kind) const;
};

// Isolated vertices and vertices with zero area get 0.
Curvatures curvatures(const Mesh& mesh);

// Colors for a scalar field: a blue-white-red diverging map when the values have both signs, else
// a sequential map, clamped at the 10% and 90% percentiles as MeshLab does. RGB in [0,1], 3 per value.
std::vector<double> colorMap(const std::vector<double>& values);

}  // namespace geoshift

#pragma once
// Error metrics between a result and a reference (docs/algorithms.md#noise-and-error-metrics).
#include <vector>

#include "geoshift/mesh.hpp"

namespace geoshift {

// sqrt(mean |a_i - b_i|^2). Throws InputError when the counts differ.
double perVertexRms(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

struct DistanceStats {
  int samples = 0;      // samples that found the target within maxDistance
  int dropped = 0;      // samples at or beyond maxDistance
  double min = 0, max = 0, mean = 0, rms = 0;
  double diagonal = 0;  // bounding-box diagonal of the sampled mesh, to divide by
};

struct PointToSurfaceOptions {
  double maxDistance = -1;  // < 0: half the target's bounding-box diagonal (MeshLab's default)
};

// One-sided distance like MeshLab's Hausdorff filter: every sample point finds its closest point
// on the target surface (exact point–triangle distance, uniform grid over the faces).
DistanceStats pointToSurface(const std::vector<Vec3>& samples, const Mesh& target,
                             const PointToSurfaceOptions& options = {});

// Mean angle in degrees between corresponding face normals. Throws InputError unless both meshes
// have the same face count.
double meanNormalAngleError(const Mesh& result, const Mesh& reference);

}  // namespace geoshift

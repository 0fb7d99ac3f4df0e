#pragma once
// Blurring mean shift of face normals over surface neighbourhoods (docs/denoising.md#the-default-pipeline):
// the normal-filtering half of the default denoiser. Each face's neighbourhood is found once on a
// support surface (faces reached across edges within r, or a log map from its centroid) and
// reused by every pass.
#include <cstddef>
#include <vector>

#include "geoshift/geodesic.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

struct FaceNeighborhoodOptions {
  double radius = 1.75;           // geodesic radius around a face centroid, in average edge lengths
  double spatialBandwidth = 0.6;  // h_s of the spatial Gaussian, in average edge lengths
  // Distances from log maps on the support (geodesic) instead of straight distances between
  // centroids of faces reached across edges. Within r = 1.75 AEL of a smoothed support the two
  // differ little and the straight ones cost a fraction (docs/denoising.md#the-default-pipeline).
  bool geodesic = false;
  ParallelOptions parallel;
};

// For face f, the faces g whose centroid lies within `radius` of f's centroid (f itself first), and
// the spatial kernel exp(-d²/2h_s²) of their distance d. Compressed rows.
struct FaceNeighborhoods {
  std::vector<int> start;          // faceCount + 1 offsets into face / spatialWeight
  std::vector<int> face;
  std::vector<float> spatialWeight;
  double radius = 0;               // absolute (the support's units)
  double spatialBandwidth = 0;     // absolute
  size_t bytes() const {
    return start.capacity() * sizeof(int) + face.capacity() * sizeof(int) + spatialWeight.capacity() * sizeof(float);
  }
};

// Neighbourhoods on `support` (it must have the faces of the meshes the normals come from).
// Identical for any thread count. Throws InputError for radius or spatialBandwidth not > 0, Cancelled
// through `progress`.
FaceNeighborhoods faceNeighborhoods(const Mesh& support, const FaceNeighborhoodOptions& options = {},
                                    const Progress& progress = {});

// One step of the blurring mean shift of the unit face normals: each face's normal moves to the
// normalised mean of its neighbours' normals weighted by spatial kernel × area × range kernel
// exp(-|n_g − n_f|² / 2h_r²). `areas` and `normals` have one entry per face (a face of zero area
// has weight zero; a zero normal stays zero). Identical for any thread count.
std::vector<Vec3> shiftFaceNormals(const FaceNeighborhoods& hoods, const std::vector<double>& areas,
                                   const std::vector<Vec3>& normals, double rangeBandwidth,
                                   const ParallelOptions& parallel = {}, const Progress& progress = {});

}  // namespace geoshift

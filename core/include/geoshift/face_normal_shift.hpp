#pragma once
// Blurring mean shift of face normals over surface neighbourhoods (docs/denoising.md#the-default-pipeline):
// the normal-filtering half of the default denoiser. Each face's neighbourhood is found once on a
// support surface (faces reached across edges within r, or a log map from its centroid) and
// reused by every pass.
#include <cstddef>
#include <span>
#include <utility>
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

// For face f, the faces g whose centroid lies within `radius` of f's centroid (f itself first, the
// others in increasing order), with the spatial kernel exp(-d²/2h_s²) of their distance d. Rows are
// stored in blocks of kBlock faces, each block in one exactly sized array, so the table never holds
// a second copy of itself. With straight distances a row holds only its faces: the weights are
// recomputed from the support's centroids when used, which halves the table
// (docs/denoising.md#speed-and-memory); geodesic distances cannot be, and are stored.
struct FaceNeighborhoods {
  static constexpr int kBlock = 4096;
  std::vector<std::vector<int>> faceBlocks;      // the rows of faces [b·kBlock, (b+1)·kBlock)
  std::vector<std::vector<float>> weightBlocks;  // geodesic: the rows' spatial weights; else empty
  std::vector<Vec3> centroids;                   // straight: the support's face centroids; else empty
  std::vector<int> start;                        // face -> offset of its row in its block; faceCount + 1
  double radius = 0;                             // absolute (the support's units)
  double spatialBandwidth = 0;                   // absolute

  int faceCount() const { return start.empty() ? 0 : static_cast<int>(start.size()) - 1; }
  // Offsets [begin, end) of f's row in faceBlocks[f / kBlock] (and weightBlocks).
  std::pair<int, int> span(int f) const {
    const int end = (f + 1) % kBlock == 0 ? static_cast<int>(faceBlocks[f / kBlock].size()) : start[f + 1];
    return {start[f], end};
  }
  std::span<const int> row(int f) const {
    const auto [b, e] = span(f);
    return {faceBlocks[f / kBlock].data() + b, static_cast<size_t>(e - b)};
  }
  // The spatial weight of the j-th face of f's row, as the shift uses it.
  float spatialWeight(int f, int j) const;
  size_t bytes() const;
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
// The same with the normals and areas of `mesh`'s faces at its positions.
std::vector<Vec3> shiftFaceNormals(const FaceNeighborhoods& hoods, const Mesh& mesh, double rangeBandwidth,
                                   const ParallelOptions& parallel = {}, const Progress& progress = {});

}  // namespace geoshift

#pragma once
// Blurring mean shift of face normals over surface neighbourhoods (docs/denoising.md#the-default-pipeline):
// the normal-filtering half of the default denoiser. Each face's neighbourhood is found once on a
// support surface (faces reached across edges within r, or a log map from its centroid) and
// reused by every pass.
#include <cstddef>
#include <span>
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
// others in increasing order), each with the spatial kernel exp(-d²/2h_s²) of their distance d.
// Rows are stored in blocks of kBlock faces, each block's entries in one exactly sized array: built
// block by block, the table never holds a second copy of itself (docs/denoising.md#speed-and-memory).
struct FaceNeighborhoods {
  struct Entry {
    int face;
    float spatialWeight;
  };
  static constexpr int kBlock = 4096;
  std::vector<std::vector<Entry>> blocks;  // faces [b·kBlock, (b+1)·kBlock)
  std::vector<int> start;                  // face -> offset of its row in its block; faceCount + 1
  double radius = 0;                       // absolute (the support's units)
  double spatialBandwidth = 0;             // absolute

  int faceCount() const { return start.empty() ? 0 : static_cast<int>(start.size()) - 1; }
  std::span<const Entry> row(int f) const {
    const std::vector<Entry>& block = blocks[f / kBlock];
    const int end = (f + 1) % kBlock == 0 ? static_cast<int>(block.size()) : start[f + 1];
    return {block.data() + start[f], static_cast<size_t>(end - start[f])};
  }
  size_t bytes() const {
    size_t n = start.capacity() * sizeof(int) + blocks.capacity() * sizeof(std::vector<Entry>);
    for (const auto& b : blocks) n += b.capacity() * sizeof(Entry);
    return n;
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

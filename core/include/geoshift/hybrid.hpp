#pragma once
// The hybrid filter of the paper's Algorithm 2: wavelet analysis to L levels, the mean shift on the
// coarse mesh (far fewer vertices), synthesis with a detail gain α per level (docs/algorithms.md#hybrid-filter).
#include <vector>

#include "geoshift/mean_shift.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift {

struct HybridOptions {
  int levels = 0;                  // 0: the mean shift on the mesh itself
  std::vector<double> alpha = {0}; // detail gain, one for all levels or one per level (0 = finest)
  // The details of the positions get the gains too (the paper smooths geometry and signal alike);
  // false keeps the input positions and filters the signal only.
  bool filterGeometry = false;
  WaveletOptions wavelet;          // its `levels` is replaced by `levels` above
  // > 0: the mean shift's spatial options (h_s, r, ε) are multiples of this absolute length instead
  // of the filtered (coarse) mesh's average edge length, so that pieces of one surface (tiles,
  // docs/tiles.md) filter with the same bandwidths.
  double unit = 0;
};

struct HybridResult {
  AttributeSet signal;             // the filtered channels on the input mesh
  std::vector<Vec3> positions;     // the input positions, or synthesised ones with filterGeometry
  std::vector<int> segment;        // with MeanShiftOptions::segments: per input vertex
  int segmentCount = 0;
  std::vector<int> vertexCounts;   // input, then after each level (the last one was filtered)
  MeanShiftResult coarse;          // the mean shift's own result on the coarse mesh
  double seconds = 0;              // analysis + mean shift + synthesis
};

// Throws what analyze, meanShift and synthesize throw (bad levels or alpha count included);
// Cancelled through `progress`.
HybridResult hybridMeanShift(const Mesh& mesh, const AttributeSet& signal, const MeanShiftOptions& options,
                             const HybridOptions& hybrid, const Progress& progress = {});

}  // namespace geoshift

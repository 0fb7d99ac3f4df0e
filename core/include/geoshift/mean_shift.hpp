#pragma once
// Riemannian mean shift and blurring mean shift of vertex signals (the paper's Algorithm 1;
// docs/algorithms.md#mean-shift), with segmentation by modes.
//
// Every vertex i starts an iterate p at itself and climbs the density estimate
//   f(p, y) = Σ_j k_s(d(p, x_j)² / h_s²) · Π_c k_r(dist_c(y_c, f_j,c)² / h_r,c²)
// by p ← exp_p(m), m the weighted mean of log_p(x_j) (eq. 6, 7), until |m| ≤ ε or k_max steps.
// The filter output at i is the range value at its mode. With passes > 1 the result of a pass is
// the signal of the next (blurring mean shift; the vertices, the domain, never move).
#include <cstdint>
#include <string>
#include <vector>

#include "geoshift/attributes.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

enum class RangeKernel {
  Gaussian,          // exp(−|y − f_j|² / 2h_r²) (eq. 9); unit vectors by their chord |y − f_j|
  NormalSimilarity,  // exp(−1 / (2h_r² (½ + ½ y·f_j)²)) (eq. 8), for unit vectors (normals)
};

enum class RangeUpdate {
  Sampled,  // the paper: the range value of an iterate is the signal interpolated at its point
  Joint,    // the paper's future work: the range value moves by its own mean shift step
};

// One attribute of the signal and how it is compared. Several channels are filtered together
// with a product kernel, one factor each.
struct SignalChannel {
  std::string attribute;         // a name in the AttributeSet
  double rangeBandwidth = 0;     // h_r in the attribute's units; 0: MeanShiftOptions::rangeBandwidth
  RangeKernel kernel = RangeKernel::Gaussian;
};

// Speed and accuracy knobs of the climb's charts and kernel loop (docs/algorithms.md#charts,
// #kernel-loop). None changes what is computed, only how closely and how fast; the tests and the
// benchmarks set them, users need not.
struct MeanShiftTuning {
  // A fresh log map at every iteration (the paper's procedure; slow, the reference) instead of
  // charts reused while the iterate stays near their centre.
  bool exactCharts = false;
  // How far (× r) an iterate may drift from its chart's centre before it takes another chart.
  double recentre = 0.25;
  // Side (× h_s) of the cubes whose vertices share one start chart; 0: a chart per vertex.
  double chartCell = 1.0;
  // Up to 4×4×4 cubes share one start chart while K·a² stays at most this (K the mean |Gaussian
  // curvature| of their cubes, a the farthest offset from the chart's centre); 0: no merging.
  double chartDistortion = 0.1;
  // Bytes of charts that blurring passes keep between passes (and a quarter more shared between
  // workers); 0 keeps none. Results are the same either way.
  long long chartCacheBytes = 1LL << 30;
  // Kernel weights in single precision (eight a vector, sums in double, within ~1e-7 relative);
  // false: double precision throughout.
  bool singlePrecisionKernel = true;
};

struct MeanShiftOptions {
  // The channels to filter; empty: every attribute of the signal, with rangeBandwidth and
  // rangeKernel below.
  std::vector<SignalChannel> channels;
  double rangeBandwidth = 0.1;                   // h_r of channels that give none
  RangeKernel rangeKernel = RangeKernel::Gaussian;  // kernel of channels when `channels` is empty
  // Spatial quantities in multiples of the support's average edge length (AEL), as in the paper.
  double spatialBandwidth = 3;  // h_s (the Gaussian's σ)
  double radius = 0;            // truncation radius r; 0: 3 h_s
  double epsilon = 0.2;         // stop when a step is at most this long
  int maxIterations = 50;       // k_max per pass
  int passes = 1;               // 1: mean shift; > 1: blurring mean shift
  // Joint: the range value moves by its own mean shift step (docs/algorithms.md#range-update).
  RangeUpdate rangeUpdate = RangeUpdate::Joint;
  // Samples weighted by their vertex area (a third of the adjacent faces' areas): the density is
  // then one of the surface, not of the vertex sampling (the paper weighs every vertex alike: false).
  bool areaWeighted = true;
  bool segments = false;  // label vertices by their modes (MeanShiftResult::segment)
  MeanShiftTuning tuning;
  ParallelOptions parallel;
};

// What the charts cost, for benchmarks and tests.
struct MeanShiftDiagnostics {
  int startCharts = 0;           // shared start charts (groups of vertices) per pass; 0 without chartCell
  long long chartsComputed = 0;  // log maps computed for charts, all passes and threads
};

struct MeanShiftResult {
  AttributeSet signal;                 // the filtered channels, same names, kinds and dims
  std::vector<SurfacePoint> modes;     // per vertex, the mode of its last pass (on the support)
  std::vector<int> iterations;         // per vertex, steps summed over the passes
  std::vector<std::uint8_t> converged; // per vertex, whether every pass stopped by ε (not k_max)
  // With options.segments: per vertex a label in [0, segmentCount), numbered in vertex order.
  // Two vertices share one when their modes are within h_s/2 (straight-line distance, a lower bound
  // of the geodesic one at that scale) and within h_r/2 in every channel, or are linked by a chain
  // of such pairs (Comaniciu–Meer).
  std::vector<int> segment;
  int segmentCount = 0;
  // Summary.
  double meanIterations = 0;  // per vertex per pass
  int maxIterations = 0;      // the most steps one vertex took in one pass
  double convergedFraction = 0;
  int threads = 1;
  double seconds = 0;
  MeanShiftDiagnostics diagnostics;
};

// Filters the signal over the support surface. The support's mesh gives the vertices, their
// connectivity and where the log and exp maps are computed (the denoiser passes a smoothed copy
// of the mesh whose normals it filters); the signal has one row per support vertex.
// Results do not depend on the thread count. Throws InputError when the signal's vertex count
// differs from the mesh's, a channel names a missing attribute, NormalSimilarity is asked of a
// non-UnitVector attribute, or a bandwidth, radius, ε, k_max or pass count is not positive and
// finite; Cancelled when the progress' cancel flag is raised (nothing is returned then).
MeanShiftResult meanShift(const SurfaceGeometry& support, const AttributeSet& signal,
                          const MeanShiftOptions& options = {}, const Progress& progress = {});

// The same with the mesh as its own support.
MeanShiftResult meanShift(const Mesh& mesh, const AttributeSet& signal, const MeanShiftOptions& options = {},
                          const Progress& progress = {});

}  // namespace geoshift

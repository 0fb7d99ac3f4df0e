#pragma once
// Private to the mean shift sources: the validated setup, charts and their store, segmentation.
// The climb and its chart supply: mean_shift_climb.hpp.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

#include "geoshift/geodesic.hpp"
#include "geoshift/mean_shift.hpp"

namespace geoshift::mean_shift_detail {

// One attribute's slice of the packed signal (rows of `width` doubles, channels side by side).
struct Channel {
  const Attribute* source;
  int offset, dim;
  bool unit;
  RangeKernel kernel;
  double invTwoHr2;  // 1 / 2h_r²
  double hr;
};

// e^x for x in [−745, 0] (kernel weights): Cody–Waite reduction x = n ln2 + r, |r| ≤ ln2/2, then a
// degree-12 Taylor polynomial of e^r (truncation error < 2e-17 there) and 2^n built in the exponent
// bits. Within a few ulp of std::exp, inlined (the kernel's exp was a third of the filter's time as a
// libm call), and the same operations natively and in wasm.
inline double kernelExp(double x) {
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00;
  if (x < -708) return 0;
  // Round to nearest by the 1.5·2^52 shift: no libm call, the same in every IEEE environment.
  constexpr double kShift = 6755399441055744.0;
  const double n = (x * kInvLn2 + kShift) - kShift;
  const double r = (x - n * kLn2Hi) - n * kLn2Lo;
  constexpr double c[13] = {1.0, 1.0, 1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 720, 1.0 / 5040, 1.0 / 40320,
                            1.0 / 362880, 1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600};
  double p = c[12];
  for (int k = 11; k >= 0; --k) p = p * r + c[k];
  const std::int64_t bits = static_cast<std::int64_t>(n + 1023) << 52;
  double scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

// Kernel exponents at or beyond this drop their entry (double precision): exp(−700) is a weight no
// sum notices; beyond, it underflows.
constexpr double kMaxExponent = 700;

struct Setup {
  const SurfaceGeometry& geometry;
  const Mesh& mesh;
  std::vector<Channel> channels;
  int width = 0;
  std::vector<double> sampleWeight;  // per vertex: its area, or 1
  std::vector<double> vertexAreas{};  // per vertex: a third of its faces' areas
  // Absolute units.
  double hs = 0, r = 0, eps = 0, invTwoHs2 = 0, r2 = 0, drift = 0, chartRadius = 0;
  double longestEdge = 0;
  double vertexArea = 0;  // the mean area per vertex
  double rangeTolerance2 = 0;
  double cell = 0;        // side of the smallest cube of vertices sharing a start chart (0: off)
  double distortion = 0;  // MeanShiftTuning::chartDistortion
  int kmax = 0;
  bool joint = false, exact = false;
  bool singlePrecision = true;  // the specialised loops' weights (MeanShiftTuning::singlePrecisionKernel)
  double weightScale = 1;       // 1 / the mean sample weight
  // The kernel loop's specialised form for this channel set (Climber::kernelSums), or General.
  enum class Loop { General, Gaussian, Similarity } loop = Loop::General;
  std::vector<double> coef{};  // per packed dimension: the 1 / 2h_r² of its channel
};

struct Climb {
  SurfacePoint mode;
  int iterations = 0;
  bool converged = true;
};

// Entries are binned on a square grid of side r/8 over [-R, R]², row by row, so that an
// iteration reads only the cells within r of its iterate (forEachRun): a chart (up to r + drift +
// anchor reach) is several times wider than the kernel's support.
constexpr size_t kChartPad = 4;
struct Chart {
  SurfacePoint base;
  // A group's start chart: how far from base (in the chart) a vertex may be to start in it.
  double reach = 0;
  // No boundary edge is nearer to base than this (the nearest boundary vertex less the longest edge),
  // so a straightest geodesic from base shorter than it cannot hit one (Climber::run).
  double clear = 0;
  std::vector<int> vertex;    // vertices within the chart's radius of base
  std::vector<double> x, y;   // and their log-map coordinates in base's frame, then kChartPad zeros
  double origin = 0, cell = 1;  // grid: cell (i, j) covers origin + [i, i+1) cell, ...
  int side = 0;
  std::vector<int> cellStart;   // side² + 1 offsets into the entries, row-major
};

// Vertices grouped by cubes of side setup.cell, or by cubes of 2 or 4 times that side where the
// surface is flat enough (MeanShiftTuning::chartDistortion); one group per vertex when the cell is
// 0. Each has the vertex nearest its centroid as anchor and the reach of its cube (its diagonal);
// groups and their order depend only on the mesh.
struct Groups {
  std::vector<int> start, vertex, anchor;  // group g: vertex[start[g] .. start[g+1])
  std::vector<double> reach;
  std::vector<int> of;  // per vertex: its group
};
Groups groupVertices(const Setup& setup);

// Charts that workers computed (in one pass, those computed twice), kept for the rest of the filter
// (every climb and pass): a worker whose own cache evicted such a chart copies it from here instead
// of computing the log map again. Within a byte budget (a quarter of MeanShiftTuning::chartCacheBytes); results
// never depend on what is kept. Thread-safe; a kept chart is never changed or removed.
class ChartStore {
 public:
  // keepFirst: keep every chart (blurring passes, which climb through the same neighbourhoods
  // again), else only those computed a second time.
  ChartStore(int vertices, int groups, std::atomic<long long>& used, long long budget, bool keepFirst)
      : byVertex_(vertices), byGroup_(groups), seenVertex_(vertices), seenGroup_(groups), used_(used),
        budget_(budget), keepFirst_(keepFirst) {}
  // Whether to keep the chart at v (group < 0) or group's that a worker just computed: in one pass,
  // most charts serve the climbs of one neighbourhood and are never needed again (copying them all
  // made the color set slower: docs/algorithms.md#charts), so only one computed before is.
  bool worthKeeping(int v, int group) {
    return (group >= 0 ? seenGroup_[group] : seenVertex_[v]).exchange(true, std::memory_order_relaxed) || keepFirst_;
  }
  // The chart at vertex v (group < 0) or group's start chart, or null.
  const Chart* find(int v, int group) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return (group >= 0 ? byGroup_[group] : byVertex_[v]).get();
  }
  void keep(int v, int group, const Chart& chart) {
    const long long bytes = bytesOf(chart);
    if (used_.fetch_add(bytes) + bytes > budget_) {
      used_ -= bytes;
      return;
    }
    auto copy = std::make_unique<const Chart>(chart);
    std::lock_guard<std::mutex> lock(mutex_);
    auto& at = group >= 0 ? byGroup_[group] : byVertex_[v];
    if (at)
      used_ -= bytes;  // another worker kept the same chart first
    else
      at = std::move(copy);
  }
  // What a chart's entries and grid take, about.
  static long long bytesOf(const Chart& c) {
    return static_cast<long long>(c.vertex.size()) * 20 + static_cast<long long>(c.cellStart.size()) * 4;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<const Chart>> byVertex_, byGroup_;
  std::vector<std::atomic<bool>> seenVertex_, seenGroup_;
  std::atomic<long long>& used_;
  long long budget_;
  bool keepFirst_;
};

// Calls run(begin, end) for each row of cells that the disc of radius r about (qx, qy) meets, over
// the columns of that row which the disc meets: the entries an iteration must look at, plus those
// of the cells the circle cuts.
template <class Run>
inline void forEachRun(const Chart& chart, double qx, double qy, double r, const Run& run) {
  const auto cellOf = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - chart.origin) / chart.cell)), 0, chart.side - 1);
  };
  const int j0 = cellOf(qy - r), j1 = cellOf(qy + r);
  for (int j = j0; j <= j1; ++j) {
    const double lo = chart.origin + j * chart.cell, hi = lo + chart.cell;
    const double gap = std::max(0.0, std::max(lo - qy, qy - hi));  // from qy to the row's nearest y
    if (gap > r) continue;
    const double half = std::sqrt(r * r - gap * gap);
    const int row = j * chart.side;
    run(chart.cellStart[row + cellOf(qx - half)], chart.cellStart[row + cellOf(qx + half) + 1]);
  }
}

// The signal rows and sample weights of a chart's entries in the chart's order, one array per
// dimension (value[d * stride + e]), so that the kernel loop reads memory in sequence. Single
// precision (Setup::singlePrecision) keeps its own copies: coordinates in units of h_s, weights
// over their mean. Gaussian loops: values less `offset` (their mean over the chart) times `scale`
// (√(log2 e / 2h_r²)), and coordinates times kSpatialScale, so that the kernel's exponent in base 2
// is a plain sum of squares.
struct Samples {
  std::vector<double> weight, value;
  std::vector<float> fx, fy, fweight, fvalue;
  double offset[4] = {};
  double scale[4] = {1, 1, 1, 1};
  size_t stride = 0;
};
// √(log2 e / 2): a distance in units of h_s times this, squared, is the spatial exponent in base 2.
constexpr double kSpatialScale = 0.84932180028801904272;

// Fills result.segment / segmentCount from result.modes and the filtered packed signal.
void segmentModes(const Setup& setup, const std::vector<double>& signal, MeanShiftResult& result);

}  // namespace geoshift::mean_shift_detail

#pragma once
// Private to the mean shift sources: one vertex's climb (Climber) and where its charts come from
// (ChartProvider). A chart is the same whoever computes it and whenever, so what the provider
// caches never changes a result (docs/algorithms.md#charts).
#include <atomic>
#include <vector>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

// Where a climb stands: the chart it computes in, the chart's samples gathered for the kernel
// loop, the iterate's coordinates (x, y) in the chart, and how far from the chart's base the
// iterate may go before it needs another chart.
struct ChartView {
  const Chart* chart = nullptr;
  const Samples* samples = nullptr;
  double x = 0, y = 0;
  double reach = 0;
};

// A worker's supply of charts. It keeps the most recent charts (an LRU of up to 64, fewer when
// they are large), the current group's start chart pinned among them, the start charts that
// blurring passes keep, and the store shared by all workers.
class ChartProvider {
 public:
  ChartProvider(const Setup& setup, LogMap logMap);

  // The chart a climb from vertex v starts in, with v's coordinates in it: the current group's
  // start chart when v is within its reach, else `own` (v's start chart that blurring passes
  // keep), else the chart at v (cached), or with exact charts a fresh log map at v.
  ChartView startChart(int v, const std::vector<double>& signal, const Chart* own);
  // A chart for an iterate at p: with exact charts a fresh log map at p; else the start chart of
  // the group of p's nearest vertex when p is within its reach (the climbs that cross a region
  // share its chart), else the chart at that vertex.
  ChartView chartFor(const SurfacePoint& p, const std::vector<double>& signal);

  // --- groups and passes (mean_shift.cpp) ---
  // The groups whose start charts chartFor continues in; null: vertex charts only.
  void setGroups(const Groups* groups) { groups_ = groups; }
  // The groups' start charts that blurring passes keep, each readable once its flag is set.
  void setGroupCharts(const std::vector<Chart>* charts, const std::vector<std::atomic<bool>>* ready) {
    groupCharts_ = charts;
    groupReady_ = ready;
  }
  void setStore(ChartStore* store) { store_ = store; }
  // The current group: its start chart (a log map at its anchor, cached and pinned while current)
  // serves every member that starts within its reach.
  void setAnchor(int group, const std::vector<double>& signal);
  // The same with a chart computed before by anchorChart() (it must outlive the climbs).
  void useAnchor(const Chart& chart);
  Chart anchorChart(int vertex, double reach);
  void clearAnchor();
  // Whether a climb from v starts in the current group's chart (v within its reach).
  bool startsInAnchor(int v) const;
  // The chart a climb from v starts in when not in its group's: a log map at v wide enough for the
  // kernel about any point of v's faces plus the drift allowance (its `reach` is v's longest edge).
  Chart vertexStartChart(int v);
  // Call before each pass: the signal changes between passes, the charts do not.
  void beginPass() { ++pass_; }
  // Log maps computed for charts (MeanShiftDiagnostics::chartsComputed).
  long long chartsComputed() const { return charts_; }

  LogMap logMap;  // the worker's solver; other workers' are forks of the first one's

 private:
  struct CachedChart {
    int vertex = -1, group = -1, pass = -1;  // a vertex's chart (group −1) or a group's start chart
    bool pinned = false;                     // the current group's: not evicted
    long long used = 0;
    double reach = 0;  // how far from the vertex the iterate may go in this chart
    Chart chart;
    Samples samples;
  };
  static constexpr int kCachedCharts = 64;
  static constexpr double kCacheBytes = 32e6;
  static int cacheSlots(const Setup& setup);

  // The chart at u (group < 0) or group's start chart (u its anchor): from the cache, the kept
  // group charts, the store, or computed; its samples gathered for this pass.
  CachedChart& cached(int u, const std::vector<double>& signal, int group = -1);
  void chartAt(Chart& chart, const SurfacePoint& base, double radius);
  // The chart at vertex v (reach: v's longest edge), into `chart`'s storage.
  void vertexChartAt(Chart& chart, int v);
  double longestEdgeAt(int u) const;
  // p's coordinates in a chart from its face's corners, when all three are in it.
  static bool locate(const Chart& chart, const Mesh& mesh, const SurfacePoint& p, Vec2& q);
  // p in the chart of its face's corner u (the corner's one-ring unfolded as its polar coordinates).
  Vec2 inVertexChart(int u, const SurfacePoint& p) const;
  // The chart's entries' signal and weights in flat arrays for the kernel loop (mean_shift_sums.cpp).
  void gather(Samples& samples, const Chart& chart, const std::vector<double>& signal) const;
  bool fast() const { return s_.loop != Setup::Loop::General; }

  const Setup& s_;
  std::vector<CachedChart> cache_;
  long long clock_ = 0, charts_ = 0;
  int pass_ = 0;
  Chart local_;  // exact charts, and the kept start chart's samples
  Samples localSamples_;
  const Chart* anchor_ = nullptr;
  Samples anchorSamples_;
  bool anchorGathered_ = false;
  CachedChart* pinned_ = nullptr;  // the cached chart anchor_ points into (setAnchor), or null
  std::vector<int> slot_;          // per vertex: its entry in anchor_, or -1
  const Groups* groups_ = nullptr;
  const std::vector<Chart>* groupCharts_ = nullptr;
  const std::vector<std::atomic<bool>>* groupReady_ = nullptr;
  ChartStore* store_ = nullptr;
  std::vector<int> order_, fill_;            // scratch of chartAt: cell of each entry, next slot of each cell
  std::vector<double> scratchX_, scratchY_;  // and its coordinates, in log-map order
};

// The start charts that blurring passes keep from their first pass (the domain does not move
// between passes): each group's chart, and those of its members that start outside it (a detour
// up a wall of a terrain puts them farther from the anchor than the cube's diagonal), within a
// byte budget. Over budget, later passes compute them again: the same results.
class KeptCharts {
 public:
  KeptCharts(const Groups& groups, bool keep, long long budget);
  bool active() const { return active_; }
  // Gives the provider the kept group charts to copy from (before each pass).
  void lend(ChartProvider& charts) const { charts.setGroupCharts(active_ ? &group_ : nullptr, &ready_); }
  // Before a group's climbs: its kept chart becomes the provider's anchor; in the first pass it is
  // computed here, with the start charts of the members outside it (any worker: same charts).
  void enterGroup(int g, ChartProvider& charts, bool firstPass);
  // The kept start chart of the k-th member of group g, or null when it starts in the group's.
  const Chart* own(int g, int k) const;
  // After a pass: drops everything when the first pass went over the budget.
  void endPass();

 private:
  const Groups& groups_;
  bool active_;
  long long budget_;
  std::vector<Chart> group_;
  std::vector<std::atomic<bool>> ready_;  // group_[g] is filled (read by other workers)
  std::vector<std::vector<Chart>> members_;  // per group, its members' in its order (empty: in the group's)
  std::atomic<long long> bytes_{0};
  std::atomic<bool> full_{false};
};

// A worker's climber: the mean shift of one vertex at a time (eq. 6, 7) over the charts its
// provider supplies. The result of run() depends only on the vertex and the signal.
class Climber {
 public:
  Climber(const Setup& setup, LogMap logMap);
  // Mean shift from vertex v over the packed signal; writes the range value at the mode to out.
  // `own`: v's start chart kept by blurring passes (ChartProvider::startChart).
  Climb run(const std::vector<double>& signal, int v, double* out, const Chart* own = nullptr);

  ChartProvider charts;

 private:
  // One iteration's weighted sums over the chart's entries within r of the iterate: Σw, Σw·dx,
  // Σw·dy, and for joint updates Σw·(tangent of the range value) into acc_.
  void sums(const ChartView& view, const std::vector<double>& signal, double& sw, double& mx, double& my);
  // generalSums serves every channel set; kernelSums the specialised ones of Setup::loop
  // (mean_shift_sums.cpp).
  void generalSums(const Chart& chart, const std::vector<double>& signal, double qx, double qy, double& sw,
                   double& mx, double& my);
  void kernelSums(const Chart& chart, const Samples& samples, double qx, double qy, double& sw, double& mx,
                  double& my);
  // The next range value: joint, the weighted mean (one Karcher step for unit vectors) from acc_;
  // sampled, the signal at p.
  void rangeStep(const std::vector<double>& signal, const SurfacePoint& p, double sw);
  // The range value of the signal at p (barycentric; unit vectors re-normalised).
  void sample(const std::vector<double>& signal, const SurfacePoint& p, double* y) const;
  // −log of the range kernel product between y and the signal row f.
  double rangeExponent(const double* y, const double* f) const;
  double rangeChange2(const double* a, const double* b) const;

  const Setup& s_;
  std::vector<double> value_, next_, acc_;
};

}  // namespace geoshift::mean_shift_detail

// Riemannian mean shift (docs/algorithms.md#mean-shift): the per-vertex climb and the passes around it.
#include "geoshift/mean_shift.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "mean_shift_climb.hpp"

namespace geoshift {

using namespace mean_shift_detail;

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("mean shift: " + what);
}


Setup makeSetup(const SurfaceGeometry& g, const AttributeSet& signal, const MeanShiftOptions& o) {
  const Mesh& mesh = g.mesh();
  require(signal.vertexCount() == mesh.vertexCount(),
          "the signal has " + std::to_string(signal.vertexCount()) + " vertices, the mesh " +
              std::to_string(mesh.vertexCount()));
  requirePositive("mean shift: spatial bandwidth h_s", o.spatialBandwidth);
  if (o.radius != 0) requirePositive("mean shift: radius (0 for 3 h_s)", o.radius);
  requirePositive("mean shift: epsilon", o.epsilon);
  requireAtLeast("mean shift: k_max", o.maxIterations, 1);
  requireAtLeast("mean shift: passes", o.passes, 1);
  requireAtLeast("mean shift: recentre", o.tuning.recentre, 0);

  std::vector<SignalChannel> wanted = o.channels;
  if (wanted.empty())
    for (const Attribute& a : signal.all()) wanted.push_back({a.name, 0, o.rangeKernel});
  require(!wanted.empty(), "no attribute to filter");

  Setup s{g, mesh, {}, 0, {}};
  for (const SignalChannel& c : wanted) {
    const Attribute& a = signal.get(c.attribute);
    const double hr = c.rangeBandwidth > 0 ? c.rangeBandwidth : o.rangeBandwidth;
    requirePositive("mean shift: range bandwidth h_r of '" + c.attribute + "'", hr);
    require(c.kernel != RangeKernel::NormalSimilarity || a.kind == AttributeKind::UnitVector,
            "the normal-similarity kernel needs a unit-vector attribute; '" + c.attribute + "' is not one");
    for (int v = 0; v < a.vertexCount(); ++v)
      for (int d = 0; d < a.dim; ++d)
        require(std::isfinite(a.row(v)[d]),
                "attribute '" + a.name + "' is not finite at vertex " + std::to_string(v));
    s.channels.push_back({&a, s.width, a.dim, a.kind == AttributeKind::UnitVector, c.kernel, 0.5 / (hr * hr), hr});
    s.width += a.dim;
  }
  const std::vector<double> area = faceAreas(mesh);
  s.vertexAreas.assign(mesh.vertexCount(), 0.0);
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int v : mesh.face(f)) s.vertexAreas[v] += area[f] / 3;
  for (double a : area) s.vertexArea += a;
  s.vertexArea /= std::max(1, mesh.vertexCount());
  s.sampleWeight = o.areaWeighted ? s.vertexAreas : std::vector<double>(mesh.vertexCount(), 1.0);
  double weightSum = 0;
  for (double w : s.sampleWeight) weightSum += w;
  s.weightScale = weightSum > 0 ? mesh.vertexCount() / weightSum : 1.0;
  s.singlePrecision = o.tuning.singlePrecisionKernel;
  for (int h = 0; h < 3 * mesh.faceCount(); ++h) s.longestEdge = std::max(s.longestEdge, g.length(h));
  const double ael = g.averageEdgeLength();
  require(ael > 0, "the mesh has no edge of positive length");
  s.hs = o.spatialBandwidth * ael;
  s.r = (o.radius > 0 ? o.radius : 3 * o.spatialBandwidth) * ael;
  s.eps = o.epsilon * ael;
  s.invTwoHs2 = 0.5 / (s.hs * s.hs);
  s.r2 = s.r * s.r;
  s.exact = o.tuning.exactCharts;
  s.drift = s.exact ? 0 : o.tuning.recentre * s.r;
  s.chartRadius = s.r + s.drift;
  requireAtLeast("mean shift: chartCell", o.tuning.chartCell, 0);
  requireAtLeast("mean shift: chartDistortion", o.tuning.chartDistortion, 0);
  if (!s.exact && o.tuning.chartCell > 0) {
    s.cell = o.tuning.chartCell * s.hs;
    s.distortion = o.tuning.chartDistortion;
  }
  s.kmax = o.maxIterations;
  s.joint = o.rangeUpdate == RangeUpdate::Joint;
  // The specialised kernel loops: Gaussian range kernels on up to 4 dimensions (Euclidean updates
  // when joint), or one normal-similarity channel with sampled updates.
  bool gaussian = s.width <= 4, unit = false;
  for (const Channel& c : s.channels) {
    gaussian = gaussian && c.kernel == RangeKernel::Gaussian;
    unit = unit || c.unit;
    for (int d = 0; d < c.dim; ++d) s.coef.push_back(c.invTwoHr2);
  }
  if (gaussian && !(s.joint && unit))
    s.loop = Setup::Loop::Gaussian;
  else if (s.channels.size() == 1 && s.width == 3 && s.channels[0].kernel == RangeKernel::NormalSimilarity && !s.joint)
    s.loop = Setup::Loop::Similarity;
  // Range changes count as converged below (ε/h_s)² in units of h_r: the same relative tolerance.
  s.rangeTolerance2 = (s.eps / s.hs) * (s.eps / s.hs);
  return s;
}

std::vector<double> pack(const Setup& s, int n) {
  std::vector<double> packed(static_cast<size_t>(n) * s.width);
  for (const Channel& c : s.channels)
    for (int v = 0; v < n; ++v) std::copy(c.source->row(v), c.source->row(v) + c.dim, &packed[v * s.width + c.offset]);
  return packed;
}

}  // namespace

MeanShiftResult meanShift(const SurfaceGeometry& support, const AttributeSet& signal, const MeanShiftOptions& options,
                          const Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Setup s = makeSetup(support, signal, options);
  const Mesh& mesh = support.mesh();
  const int n = mesh.vertexCount();

  MeanShiftResult result;
  result.threads = resolveThreads(options.parallel.threads);
  result.modes.assign(n, SurfacePoint{});
  result.iterations.assign(n, 0);
  result.converged.assign(n, 1);

  LogMap first(support);
  std::vector<Climber> climbers;
  climbers.reserve(result.threads);
  climbers.emplace_back(s, std::move(first));
  for (int w = 1; w < result.threads; ++w) climbers.emplace_back(s, climbers.front().charts.logMap.fork());

  const Groups groups = groupVertices(s);
  for (Climber& c : climbers) c.charts.setGroups(&groups);
  const int groupCount = static_cast<int>(groups.anchor.size());
  if (s.cell > 0) result.diagnostics.startCharts = groupCount;
  ParallelOptions parallel = options.parallel;
  if (s.cell > 0) parallel.chunk = 1;  // a group holds up to ~200 vertices: one per hand-out keeps progress prompt
  std::vector<double> current = pack(s, n), next(current.size());
  // Blurring passes climb from the same vertices over the same domain: keep the start charts.
  KeptCharts kept(groups, s.cell > 0 && options.passes > 1 && options.tuning.chartCacheBytes > 0,
                  options.tuning.chartCacheBytes);
  std::atomic<long long> stored{0};  // bytes of the charts kept in the store
  ChartStore store(n, groupCount, stored, options.tuning.chartCacheBytes / 4, options.passes > 1);
  if (!s.exact && options.tuning.chartCacheBytes > 0)
    for (Climber& c : climbers) c.charts.setStore(&store);
  std::vector<int> passIterations(n);
  long long total = 0;
  for (int pass = 0; pass < options.passes; ++pass) {
    const std::string stage =
        options.passes == 1 ? "mean shift" : "blurring pass " + std::to_string(pass + 1) + "/" + std::to_string(options.passes);
    for (Climber& c : climbers) {
      c.charts.beginPass();
      kept.lend(c.charts);
    }
    parallelFor(groupCount, parallel, progress, stage, double(pass) / options.passes,
                double(pass + 1) / options.passes, [&](int g, int worker) {
                  Climber& climber = climbers[worker];
                  // The group's start chart: kept from the first pass, or the provider's own.
                  if (kept.active())
                    kept.enterGroup(g, climber.charts, pass == 0);
                  else if (s.cell > 0)
                    climber.charts.setAnchor(g, current);
                  for (int k = groups.start[g]; k < groups.start[g + 1]; ++k) {
                    const int v = groups.vertex[k];
                    const Chart* own = kept.active() ? kept.own(g, k - groups.start[g]) : nullptr;
                    const Climb c = climber.run(current, v, &next[static_cast<size_t>(v) * s.width], own);
                    result.modes[v] = c.mode;
                    passIterations[v] = c.iterations;
                    if (!c.converged) result.converged[v] = 0;
                  }
                  climber.charts.clearAnchor();
                });
    kept.endPass();
    for (int v = 0; v < n; ++v) {
      result.iterations[v] += passIterations[v];
      result.maxIterations = std::max(result.maxIterations, passIterations[v]);
      total += passIterations[v];
    }
    current.swap(next);
  }

  for (const Climber& c : climbers) result.diagnostics.chartsComputed += c.charts.chartsComputed();
  result.signal = AttributeSet(n);
  for (const Channel& c : s.channels) {
    std::vector<double> values(static_cast<size_t>(n) * c.dim);
    for (int v = 0; v < n; ++v)
      std::copy(&current[v * s.width + c.offset], &current[v * s.width + c.offset] + c.dim, &values[v * c.dim]);
    result.signal.set(c.source->name, c.dim, c.source->kind, std::move(values));
  }
  if (options.segments) {
    progress.step(1.0, "segments");
    segmentModes(s, current, result);
  }
  result.meanIterations = n > 0 ? double(total) / (double(n) * options.passes) : 0;
  result.convergedFraction =
      n > 0 ? double(std::count(result.converged.begin(), result.converged.end(), 1)) / n : 1.0;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

MeanShiftResult meanShift(const Mesh& mesh, const AttributeSet& signal, const MeanShiftOptions& options,
                          const Progress& progress) {
  const SurfaceGeometry geometry(mesh);
  return meanShift(geometry, signal, options, progress);
}

}  // namespace geoshift

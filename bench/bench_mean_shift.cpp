// Mean shift with the paper's parameter sets (docs/algorithms.md#presets) on tori of 10k and 100k vertices
// and on terrains (procedural, and real LiDAR when ../shared/data is there), on one thread and on
// all: milliseconds per vertex (the paper's Table 2 works out to about 1 ms per vertex for MS and
// 3 ms for BMS on one 3 GHz thread; our target is 20× less per thread).
// Arguments: workload, vertices (10k / 100k), threads (1 / 0 = all), charts (0 shared, the default /
// 1 exact / 2 shared over cubes of chartCell only, chartDistortion = 0 / 3 no charts kept beyond a
// worker's own cache, chartCacheBytes = 0; all MeanShiftTuning).
// Counters: ms_per_vertex (wall time / vertices), iterations (mean per vertex per pass), converged,
// start_charts (groups), log_maps (charts computed, all passes).
// Every run filters every vertex of the mesh once (one benchmark iteration).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geoshift/geometry.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/terrain.hpp"
#include "geoshift/wavelet.hpp"

namespace {

using namespace geoshift;

struct Fixture {
  Mesh mesh;
  SurfaceGeometry geometry;
  AttributeSet color, normal, scalar;
  explicit Fixture(int vertices)
      : mesh(buildMesh(vertices > 50000 ? shapes::torus(500, 200) : shapes::torus(160, 64)).mesh), geometry(mesh) {
    const int n = mesh.vertexCount();
    // Deterministic pseudo-noise, the same on every machine.
    std::uint64_t state = 88172645463325252ULL;
    const auto noise = [&] {
      state ^= state << 13;
      state ^= state >> 7;
      state ^= state << 17;
      return static_cast<double>(state % 2000001) / 1e6 - 1.0;
    };
    std::vector<double> rgb, veg, nrm;
    for (int v = 0; v < n; ++v) {
      const Vec3 p = mesh.position(v);
      const bool a = std::sin(6 * std::atan2(p.y(), p.x())) > 0;  // six color sectors around the torus
      for (double c : {a ? 0.9 : 0.1, 0.4, a ? 0.2 : 0.8}) rgb.push_back(c + 0.1 * noise());
      veg.push_back((a ? 20.0 : 2.0) + 3 * noise());  // vegetation height in meters, two stands
    }
    for (const Vec3& v : vertexNormals(mesh)) {
      const Vec3 d = (v + 0.3 * Vec3(noise(), noise(), noise())).normalized();
      nrm.insert(nrm.end(), {d.x(), d.y(), d.z()});
    }
    color = AttributeSet(n);
    color.set("COLOR", 3, AttributeKind::Euclidean, rgb);
    normal = AttributeSet(n);
    normal.set("NORMAL", 3, AttributeKind::UnitVector, nrm);
    scalar = AttributeSet(n);
    scalar.set("_VEGETATION_HEIGHT", 1, AttributeKind::Euclidean, veg);
  }
};

const Fixture& fixture(int vertices) {
  static std::map<int, std::unique_ptr<Fixture>> cache;
  auto& f = cache[vertices];
  if (!f) f = std::make_unique<Fixture>(vertices);
  return *f;
}

// 0 color, 1 denoise normals (§4.1), 2 terrain-ms, 3 terrain-bms, 4 curvature-ms, 5 curvature-bms
// (curvature sets on the vegetation scalar: same bandwidths, the signal's scale does not change the cost much).
const char* const kNames[] = {"color", "denoise-normals", "terrain-ms", "terrain-bms", "curvature-ms", "curvature-bms"};

// The counters of a filter run over n vertices (see the header).
void report(benchmark::State& state, const MeanShiftResult& r, int n) {
  state.counters["ms_per_vertex"] = benchmark::Counter(r.seconds * 1e3 / n);
  state.counters["iterations"] = benchmark::Counter(r.meanIterations);
  state.counters["converged"] = benchmark::Counter(r.convergedFraction);
  state.counters["vertices"] = benchmark::Counter(n);
  state.counters["start_charts"] = benchmark::Counter(r.diagnostics.startCharts);
  state.counters["log_maps"] = benchmark::Counter(static_cast<double>(r.diagnostics.chartsComputed));
}

void BM_MeanShift(benchmark::State& state) {
  const int workload = static_cast<int>(state.range(0));
  const Fixture& f = fixture(static_cast<int>(state.range(1)));
  MeanShiftOptions o;
  const AttributeSet* signal = &f.scalar;
  switch (workload) {
    case 0: o = filterPreset("color").options; signal = &f.color; break;
    case 1:
      o.channels = {{"NORMAL", 0.45, RangeKernel::NormalSimilarity}};
      o.radius = 4;
      o.spatialBandwidth = 3;
      o.epsilon = 0.2;
      o.maxIterations = 50;
      signal = &f.normal;
      break;
    case 2: o = filterPreset("terrain-ms").options; break;
    case 3: o = filterPreset("terrain-bms").options; break;
    case 4: o = filterPreset("curvature-ms").options; break;
    default: o = filterPreset("curvature-bms").options; break;
  }
  o.parallel.threads = static_cast<int>(state.range(2));
  o.tuning.exactCharts = state.range(3) == 1;
  if (state.range(3) == 2) o.tuning.chartDistortion = 0;
  if (state.range(3) == 3) o.tuning.chartCacheBytes = 0;
  MeanShiftResult r;
  for (auto _ : state) r = meanShift(f.geometry, *signal, o);
  const int n = f.mesh.vertexCount();
  state.SetLabel(std::string(kNames[workload]) + (o.tuning.exactCharts ? " exact" : "") +
                 (state.range(3) == 2 ? " unmerged" : state.range(3) == 3 ? " nothing kept" : "") +
                 " threads=" + std::to_string(r.threads));
  report(state, r, n);
}

// The terrain sets on what the paper times them on: a terrain's coarse mesh after six wavelet
// levels (the paper's Table 2; the hybrid filter's mean shift), here a 320 x 320 procedural
// terrain's (10,946 vertices), with its vegetation height. Its hills are a few h_s across, so
// climbs go much farther than on the torus. Arguments: workload (2 terrain-ms, 3 terrain-bms),
// threads (1 / 0 = all).
// A terrain's attributes analysed to six wavelet levels as the terrain presets do (`geoshift filter
// --preset terrain-*`): the coarse mesh and its lifted attributes.
struct TerrainFixture {
  Multiresolution mr;
  std::unique_ptr<SurfaceGeometry> geometry;
  TerrainFixture(const TerrainMesh& terrain, const std::vector<std::string>& names) {
    const Mesh mesh = buildMesh(terrain.soup()).mesh;
    AttributeSet signal(mesh.vertexCount());
    for (const std::string& name : names) {
      const Attribute& a = terrain.attributes.get(name);
      signal.set(a.name, 1, AttributeKind::Euclidean, a.values);
    }
    WaveletOptions w;
    w.levels = 6;
    mr = analyze(mesh, signal, w);
    geometry = std::make_unique<SurfaceGeometry>(mr.coarse);
  }
};

// A 320 × 320 procedural terrain and its vegetation height.
const TerrainFixture& proceduralFixture() {
  static const TerrainFixture f = [] {
    TerrainOptions t;
    t.size = 320;
    t.seed = 1;
    return TerrainFixture(proceduralTerrain(t), {"_VEGETATION_HEIGHT"});
  }();
  return f;
}

// Real LiDAR: PDAL's autzen_trim.las (110k points of a town's edge: ground, trees, roofs) from
// ../shared/data, triangulated as `geoshift terrain` does, with the height above ground and the
// class as `--signal terrain` filters them; null when the shared data is absent.
const TerrainFixture* lidarFixture() {
  static const std::unique_ptr<TerrainFixture> f = []() -> std::unique_ptr<TerrainFixture> {
    const std::string path = std::string(GEOSHIFT_SHARED_DATA) + "/pdal_testdata/las/autzen_trim.las";
    if (!std::ifstream(path)) return nullptr;
    return std::make_unique<TerrainFixture>(pointTerrain(readLas(path)),
                                            std::vector<std::string>{"_HEIGHT_ABOVE_GROUND", "_CLASS"});
  }();
  return f.get();
}

// Arguments: workload (2 terrain-ms, 3 terrain-bms), threads (1 / 0 = all), data (0 procedural,
// 1 LiDAR).
void BM_MeanShiftTerrain(benchmark::State& state) {
  const bool lidar = state.range(2) == 1;
  const TerrainFixture* found = lidar ? lidarFixture() : &proceduralFixture();
  if (!found) {
    state.SkipWithError("../shared/data/pdal_testdata/las/autzen_trim.las not found (shared data absent)");
    return;
  }
  const TerrainFixture& f = *found;
  const int workload = static_cast<int>(state.range(0));
  MeanShiftOptions o = filterPreset(kNames[workload]).options;
  o.parallel.threads = static_cast<int>(state.range(1));
  MeanShiftResult r;
  for (auto _ : state) r = meanShift(*f.geometry, f.mr.coarseAttributes, o);
  const int n = f.mr.coarse.vertexCount();
  state.SetLabel(std::string(kNames[workload]) + (lidar ? " autzen LiDAR" : " terrain") +
                 " threads=" + std::to_string(r.threads));
  report(state, r, n);
}

BENCHMARK(BM_MeanShiftTerrain)
    ->Args({2, 1, 0})
    ->Args({2, 0, 0})
    ->Args({3, 1, 0})
    ->Args({3, 0, 0})
    ->Args({2, 1, 1})
    ->Args({2, 0, 1})
    ->Args({3, 1, 1})
    ->Args({3, 0, 1})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void arguments(benchmark::internal::Benchmark* b) {
  for (int workload = 0; workload < 6; ++workload) {
    for (int threads : {1, 0}) b->Args({workload, 10000, threads, 0});
    b->Args({workload, 10000, 1, 1});
  }
  // 100k vertices: the color and denoising sets; the wider kernels take minutes a run there.
  for (int workload = 0; workload < 2; ++workload)
    for (int threads : {1, 0}) b->Args({workload, 100000, threads, 0});
  // What keeping charts for later climbs and passes saves (blurring passes: the cubes' charts too).
  for (int workload : {2, 3}) b->Args({workload, 10000, 1, 3});
  // What merging the cubes of flat regions saves (the 100k torus is flat enough; the 10k one is not).
  for (int workload = 0; workload < 2; ++workload) b->Args({workload, 100000, 1, 2});
}

// What sharing charts costs in accuracy on a curved surface: the filtered signal with shared and
// reused charts against fresh charts at every iteration, same run otherwise (all threads).
// Arguments: workload (0 color, 1 curvature-ms), vertices, merge (1: the default chartDistortion,
// 0: cubes of chartCell only). Counters: the largest, mean, 99th and 99.9th percentile absolute
// differences, and the speed-up over exact charts.
void BM_ChartAccuracy(benchmark::State& state) {
  const int workload = static_cast<int>(state.range(0));
  const int vertices = static_cast<int>(state.range(1));
  const Fixture& f = fixture(vertices);
  MeanShiftOptions o = workload == 0 ? filterPreset("color").options : filterPreset("curvature-ms").options;
  const AttributeSet& signal = workload == 0 ? f.color : f.scalar;
  const std::string name = workload == 0 ? "COLOR" : "_VEGETATION_HEIGHT";
  o.parallel.threads = 0;
  if (state.range(2) == 0) o.tuning.chartDistortion = 0;
  // The exact run of a workload and mesh serves both merge settings.
  static std::map<std::pair<int, int>, MeanShiftResult> exactRuns;
  MeanShiftResult fast;
  for (auto _ : state) {
    fast = meanShift(f.geometry, signal, o);
    auto& exact = exactRuns[{workload, vertices}];
    if (exact.signal.vertexCount() == 0) {
      MeanShiftOptions e = o;
      e.tuning.exactCharts = true;
      exact = meanShift(f.geometry, signal, e);
    }
  }
  const MeanShiftResult& exact = exactRuns[{workload, vertices}];
  const auto& a = fast.signal.get(name).values;
  const auto& b = exact.signal.get(name).values;
  std::vector<double> diff(a.size());
  for (size_t i = 0; i < a.size(); ++i) diff[i] = std::abs(a[i] - b[i]);
  double sum = 0, range = 0;
  for (double d : diff) sum += d;
  for (double x : signal.get(name).values) range = std::max(range, std::abs(x));
  std::sort(diff.begin(), diff.end());
  const auto quantile = [&](double q) { return diff[static_cast<size_t>(q * static_cast<double>(diff.size() - 1))]; };
  state.SetLabel(std::string(workload == 0 ? "color" : "curvature-ms") + " shared vs exact charts" +
                 (state.range(2) == 0 ? ", unmerged" : ""));
  state.counters["max_abs_diff"] = benchmark::Counter(diff.back());
  state.counters["mean_abs_diff"] = benchmark::Counter(sum / static_cast<double>(diff.size()));
  state.counters["p99"] = benchmark::Counter(quantile(0.99));
  state.counters["p999"] = benchmark::Counter(quantile(0.999));
  state.counters["signal_max"] = benchmark::Counter(range);
  state.counters["speedup"] = benchmark::Counter(exact.seconds / fast.seconds);
  state.counters["start_charts"] = benchmark::Counter(fast.diagnostics.startCharts);
}

// The 10k torus is too curved for merged cubes (both settings give the same groups); the 100k one
// merges most of them. Exact charts on 100k vertices take a minute or two.
BENCHMARK(BM_ChartAccuracy)
    ->Args({0, 10000, 1})
    ->Args({1, 10000, 1})
    ->Args({0, 100000, 1})
    ->Args({0, 100000, 0})
    ->Args({1, 100000, 1})
    ->Args({1, 100000, 0})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BM_MeanShift)->Apply(arguments)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

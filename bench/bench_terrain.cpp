// Terrain construction: the procedural generator (1M vertices should take well under 1 s), the
// 2.5D Delaunay triangulation and a whole LiDAR-like point terrain (with height above ground).
// us_per_point is wall time per input point.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "geoshift/terrain.hpp"

using namespace geoshift;

namespace {

// Uniform points with a seeded LCG (no std distributions): the same set on every machine.
std::vector<Vec3> randomPoints(int n, std::uint64_t seed) {
  std::vector<Vec3> p(n);
  std::uint64_t s = seed;
  auto next = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) * 0x1.0p-53;
  };
  for (auto& q : p) {
    const double x = next() * 1000.0, y = next() * 1000.0;
    q = Vec3(x, y, next() * 30.0);
  }
  return p;
}

benchmark::Counter perPoint(int n) {
  return benchmark::Counter(n / 1e6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

static void BM_ProceduralTerrain(benchmark::State& state) {
  TerrainOptions o;
  o.size = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(proceduralTerrain(o));
  const int n = o.size * o.size;
  state.counters["vertices"] = n;
  state.counters["us_per_point"] = perPoint(n);
}
BENCHMARK(BM_ProceduralTerrain)->Arg(257)->Arg(1001)->Unit(benchmark::kMillisecond);

static void BM_Delaunay(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto p = randomPoints(n, 1);
  for (auto _ : state) benchmark::DoNotOptimize(delaunay2d(p));
  state.counters["points"] = n;
  state.counters["us_per_point"] = perPoint(n);
}
BENCHMARK(BM_Delaunay)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

// The grid of a procedural terrain as a point set: cocircular everywhere, the predicates' worst case.
static void BM_DelaunayGrid(benchmark::State& state) {
  TerrainOptions o;
  o.size = static_cast<int>(state.range(0));
  const auto p = proceduralTerrain(o).positions;
  for (auto _ : state) benchmark::DoNotOptimize(delaunay2d(p));
  state.counters["points"] = static_cast<double>(p.size());
  state.counters["us_per_point"] = perPoint(static_cast<int>(p.size()));
}
BENCHMARK(BM_DelaunayGrid)->Arg(1001)->Unit(benchmark::kMillisecond);

// 1M points, a quarter of them ground: triangulation of all, ground TIN, heights above ground.
static void BM_PointTerrain(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  TerrainPoints pts;
  pts.positions = randomPoints(n, 2);
  pts.classes.resize(n);
  for (int i = 0; i < n; ++i) pts.classes[i] = i % 4 == 0 ? 2 : 5;
  for (auto _ : state) benchmark::DoNotOptimize(pointTerrain(pts));
  state.counters["points"] = n;
  state.counters["us_per_point"] = perPoint(n);
}
BENCHMARK(BM_PointTerrain)->Arg(1000000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

// Exp map (straightest geodesics) of length 3 AEL from random face points in random directions, on
// icosphere level 7 (163,842 vertices) and a 317 x 317 jittered grid (100,489 vertices). One call
// per iteration: the Time column is the cost of one call; `per_call` repeats it as a counter and
// `faces` is the mean number of faces crossed per call. Target (brief): 2.5 µs per call.
// Argument 0 takes the starts in random order (every call begins with cache misses: the worst
// case); 1 takes them sorted by face, as a filter sweeping the mesh in index order would. The
// level-3 icosphere (642 vertices) fits in cache and shows the arithmetic cost alone.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "geoshift/geodesic.hpp"
#include "geoshift/shapes.hpp"

namespace {

struct Scene {
  geoshift::Mesh mesh;
  geoshift::SurfaceGeometry geometry{mesh};
  std::vector<geoshift::SurfacePoint> starts, sortedStarts;
  std::vector<geoshift::Vec2> vectors;

  // Samples drawn up front so that the timed loop holds only the exp map; many more than fit in a
  // cache so that the starts are as scattered as in a filter's sweep over a large mesh.
  explicit Scene(geoshift::Mesh m) : mesh(std::move(m)) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    std::uniform_int_distribution<int> face(0, mesh.faceCount() - 1);
    const double len = 3 * geometry.averageEdgeLength();
    for (int i = 0; i < (1 << 16); ++i) {
      geoshift::Vec3 b(unit(rng), unit(rng), unit(rng));
      starts.push_back({face(rng), b / b.sum()});
      const double a = 2 * std::numbers::pi * unit(rng);
      vectors.emplace_back(len * std::cos(a), len * std::sin(a));
    }
    sortedStarts = starts;
    std::sort(sortedStarts.begin(), sortedStarts.end(),
              [](const auto& a, const auto& b) { return a.face < b.face; });
  }
};

const Scene& sphere() {
  static const Scene scene(geoshift::buildMesh(geoshift::shapes::icosphere(7)).mesh);
  return scene;
}

const Scene& smallSphere() {
  static const Scene scene(geoshift::buildMesh(geoshift::shapes::icosphere(3)).mesh);
  return scene;
}

const Scene& plane() {
  static const Scene scene(geoshift::buildMesh(geoshift::shapes::grid(317, 0.2)).mesh);
  return scene;
}

void run(benchmark::State& state, const Scene& scene) {
  const auto& starts = state.range(0) ? scene.sortedStarts : scene.starts;
  const size_t n = starts.size();
  size_t i = 0;
  int64_t faces = 0;
  for (auto _ : state) {
    const geoshift::ExpMapResult r = geoshift::expMap(scene.geometry, starts[i], scene.vectors[i]);
    faces += r.facesCrossed;
    benchmark::DoNotOptimize(r.end);
    if (++i == n) i = 0;
  }
  const double calls = static_cast<double>(state.iterations());
  state.counters["per_call"] = benchmark::Counter(calls, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["faces"] = static_cast<double>(faces) / calls;
}

void BM_ExpMap3AEL_Icosphere7(benchmark::State& state) { run(state, sphere()); }
void BM_ExpMap3AEL_JitteredGrid317(benchmark::State& state) { run(state, plane()); }
void BM_ExpMap3AEL_Icosphere3(benchmark::State& state) { run(state, smallSphere()); }

}  // namespace

BENCHMARK(BM_ExpMap3AEL_Icosphere7)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ExpMap3AEL_JitteredGrid317)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ExpMap3AEL_Icosphere3)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();

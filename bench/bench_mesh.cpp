// Mesh construction throughput: welding and half-edge building on ~160k-vertex meshes.
#include <benchmark/benchmark.h>

#include "geoshift/mesh.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

static void BM_BuildWelded(benchmark::State& state) {
  const TriangleSoup s = shapes::icosphere(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(buildMesh(s));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.positions.size()));
  state.counters["vertices"] = static_cast<double>(s.positions.size());
}
BENCHMARK(BM_BuildWelded)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);

// Every face with its own three vertices, as a glTF split along all seams: the welding case.
static void BM_BuildFromSplitSoup(benchmark::State& state) {
  const TriangleSoup s = shapes::unwelded(shapes::icosphere(static_cast<int>(state.range(0))));
  for (auto _ : state) benchmark::DoNotOptimize(buildMesh(s));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.positions.size()));
  state.counters["caller_vertices"] = static_cast<double>(s.positions.size());
}
BENCHMARK(BM_BuildFromSplitSoup)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);

static void BM_VertexRotation(benchmark::State& state) {
  const Mesh m = buildMesh(shapes::icosphere(7)).mesh;
  for (auto _ : state) {
    long sum = 0;
    for (int v = 0; v < m.vertexCount(); ++v) m.forEachOutgoing(v, [&](int h) { sum += m.head(h); });
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * m.vertexCount());
}
BENCHMARK(BM_VertexRotation)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

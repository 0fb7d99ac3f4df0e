// The hybrid filter (Algorithm 2) against the direct filter on a procedural terrain: the paper's
// terrain-bms set on _VEGETATION_HEIGHT, L = 0 (direct), 2, 4, 6 wavelet levels, all threads.
// Counters: seconds, filtered (vertices the mean shift ran on), speedup over L = 0 (run L = 0 first:
// the benchmarks run in the order registered). The terrain has 201 x 201 = 40,401 vertices, the
// size of the paper's Smoky Mountains model after six levels.
#include <benchmark/benchmark.h>

#include "geoshift/hybrid.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/terrain.hpp"

namespace {

using namespace geoshift;

struct Fixture {
  Mesh mesh;
  AttributeSet signal;
  Fixture() {
    TerrainOptions t;
    t.size = 201;
    t.seed = 7;
    const TerrainMesh terrain = proceduralTerrain(t);
    mesh = buildMesh(terrain.soup()).mesh;
    signal = AttributeSet(mesh.vertexCount());
    const Attribute& v = terrain.attributes.get("_VEGETATION_HEIGHT");
    signal.set(v.name, 1, AttributeKind::Euclidean, v.values);
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

double directSeconds = 0;

void BM_Hybrid(benchmark::State& state) {
  const Fixture& f = fixture();
  const FilterPreset& preset = filterPreset("terrain-bms");
  HybridOptions h;
  h.levels = static_cast<int>(state.range(0));
  h.alpha = {0};
  HybridResult r;
  for (auto _ : state) r = hybridMeanShift(f.mesh, f.signal, preset.options, h);
  if (h.levels == 0) directSeconds = r.seconds;
  state.counters["seconds"] = r.seconds;
  state.counters["filtered"] = r.vertexCounts.back();
  state.counters["vertices"] = f.mesh.vertexCount();
  if (directSeconds > 0) state.counters["speedup"] = directSeconds / r.seconds;
}

BENCHMARK(BM_Hybrid)->Arg(0)->Arg(2)->Arg(4)->Arg(6)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

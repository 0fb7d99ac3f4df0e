// Geometry kernels on icosphere level 7 (163,842 vertices, 327,680 faces). Items = vertices
// (point-to-surface: samples; Taubin: vertices × iterations).
#include <benchmark/benchmark.h>

#include "geoshift/curvature.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/smoothing.hpp"

namespace {

const geoshift::Mesh& sphere() {
  static const geoshift::Mesh mesh = geoshift::buildMesh(geoshift::shapes::icosphere(7)).mesh;
  return mesh;
}

void BM_Curvatures(benchmark::State& state) {
  const geoshift::Mesh& mesh = sphere();
  for (auto _ : state) benchmark::DoNotOptimize(geoshift::curvatures(mesh));
  state.SetItemsProcessed(state.iterations() * mesh.vertexCount());
}

void BM_VertexNormals(benchmark::State& state) {
  const geoshift::Mesh& mesh = sphere();
  for (auto _ : state) benchmark::DoNotOptimize(geoshift::vertexNormals(mesh));
  state.SetItemsProcessed(state.iterations() * mesh.vertexCount());
}

void BM_TaubinSmooth10(benchmark::State& state) {
  const auto weights = static_cast<geoshift::LaplacianWeights>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    geoshift::Mesh mesh = sphere();
    state.ResumeTiming();
    geoshift::taubinSmooth(mesh, {10, 0.5, -0.53, weights});
    benchmark::DoNotOptimize(mesh.positions().data());
  }
  state.SetItemsProcessed(state.iterations() * sphere().vertexCount() * 10);
  state.SetLabel(weights == geoshift::LaplacianWeights::Uniform    ? "uniform"
                 : weights == geoshift::LaplacianWeights::Fujiwara ? "fujiwara"
                                                                   : "cotangent");
}

// Samples: the vertices of a slightly larger sphere, so every query starts off the surface.
void BM_PointToSurface(benchmark::State& state) {
  const geoshift::Mesh& target = sphere();
  std::vector<geoshift::Vec3> samples = target.positions();
  for (geoshift::Vec3& p : samples) p *= 1.002;
  for (auto _ : state) benchmark::DoNotOptimize(geoshift::pointToSurface(samples, target));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(samples.size()));
}

}  // namespace

BENCHMARK(BM_Curvatures)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VertexNormals)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TaubinSmooth10)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PointToSurface)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

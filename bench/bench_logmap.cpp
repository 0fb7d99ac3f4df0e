// Log map (DGPC) from face points, one LogMap reused across calls as a filter would use it.
// Meshes: icosphere level 7 (163,842 vertices) and a 317×317 jittered grid (100,489 vertices).
// Argument: radius in average edge lengths. Counters: us_per_call, vertices (entries per call).
// Sources: a fixed pseudo-random list of 1000 faces, visited in turn, so the caches see a new
// neighbourhood on every call (the target: under 10 µs at 4 AEL). BM_LogMapWhole: the
// whole mesh from one vertex (radius ∞, as `geoshift geodesic` without --radius does it), where the
// queue holds a front of ~1000 vertices.
//
// The other cases take a call apart:
//  - Ordered: every face in index order, as a filter sweeping the mesh meets its sources;
//  - Warm: eight sources in turn (their neighbourhoods stay in cache, and the branch predictor
//    learns their eight calls by heart): the arithmetic alone;
//  - SmallSphere: icosphere level 3 (642 vertices: the whole solver fits in L2) from the 1000
//    sources: no cache misses, but every call's branches as unpredictable as on a large mesh.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <limits>
#include <random>

#include "geoshift/geodesic.hpp"
#include "geoshift/shapes.hpp"

namespace {

struct Fixture {
  geoshift::Mesh mesh;
  geoshift::SurfaceGeometry geometry;
  std::vector<geoshift::SurfacePoint> sources, ordered;

  explicit Fixture(const geoshift::TriangleSoup& soup)
      : mesh(geoshift::buildMesh(soup).mesh), geometry(mesh) {
    std::mt19937 engine(2024);
    for (int i = 0; i < 1000; ++i) {
      const int f = static_cast<int>(engine() % static_cast<std::uint32_t>(mesh.faceCount()));
      sources.push_back(geoshift::SurfacePoint::inFace(mesh, f, geoshift::Vec3(0.2, 0.3, 0.5)));
    }
    for (int f = 0; f < mesh.faceCount(); ++f)
      ordered.push_back(geoshift::SurfacePoint::inFace(mesh, f, geoshift::Vec3(0.2, 0.3, 0.5)));
  }
};

const Fixture& sphere() {
  static const Fixture fixture(geoshift::shapes::icosphere(7));
  return fixture;
}

const Fixture& smallSphere() {
  static const Fixture fixture(geoshift::shapes::icosphere(3));
  return fixture;
}

const Fixture& plane() {
  static const Fixture fixture(geoshift::shapes::grid(317, 0.2));
  return fixture;
}

enum class Sources { Random, Warm, Ordered };

void run(benchmark::State& state, const Fixture& fixture, Sources which = Sources::Random) {
  geoshift::LogMap logMap(fixture.geometry);
  const double radius = static_cast<double>(state.range(0)) * fixture.geometry.averageEdgeLength();
  const auto& sources = which == Sources::Ordered ? fixture.ordered : fixture.sources;
  const std::size_t count = which == Sources::Warm ? 8 : sources.size();
  std::size_t next = 0;
  std::int64_t reached = 0;
  for (auto _ : state) {
    const auto& entries = logMap.compute(sources[next], radius);
    reached += static_cast<std::int64_t>(entries.size());
    benchmark::DoNotOptimize(entries.data());
    if (++next == count) next = 0;
  }
  state.SetItemsProcessed(state.iterations());
  // kIsRate divides by the elapsed time, kInvert turns that into seconds per (1e-6 call) = µs/call.
  state.counters["us_per_call"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 1e-6,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["vertices"] = benchmark::Counter(static_cast<double>(reached), benchmark::Counter::kAvgIterations);
}

void BM_LogMapSphere(benchmark::State& state) { run(state, sphere()); }
void BM_LogMapPlane(benchmark::State& state) { run(state, plane()); }
void BM_LogMapSphereOrdered(benchmark::State& state) { run(state, sphere(), Sources::Ordered); }
void BM_LogMapPlaneOrdered(benchmark::State& state) { run(state, plane(), Sources::Ordered); }
void BM_LogMapSphereWarm(benchmark::State& state) { run(state, sphere(), Sources::Warm); }
void BM_LogMapPlaneWarm(benchmark::State& state) { run(state, plane(), Sources::Warm); }
void BM_LogMapSmallSphere(benchmark::State& state) { run(state, smallSphere()); }

void BM_LogMapWhole(benchmark::State& state) {
  const Fixture& fixture = state.range(0) == 0 ? sphere() : plane();
  geoshift::LogMap logMap(fixture.geometry);
  for (auto _ : state) benchmark::DoNotOptimize(logMap.computeFromVertex(0, std::numeric_limits<double>::infinity()).data());
  state.SetLabel(state.range(0) == 0 ? "icosphere 164k" : "grid 100k, from a corner");
}

}  // namespace

BENCHMARK(BM_LogMapSphere)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapPlane)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapSphereOrdered)->Arg(4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapPlaneOrdered)->Arg(4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapSphereWarm)->Arg(4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapPlaneWarm)->Arg(4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapSmallSphere)->Arg(4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LogMapWhole)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

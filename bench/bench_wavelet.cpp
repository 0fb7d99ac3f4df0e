// Wavelet analysis and synthesis on a procedural fractal terrain (a grid heightfield with one scalar
// attribute), 100k and 1M vertices, L = 2..12. Counters: microseconds per input vertex per level,
// microseconds per processed vertex (the sum of the live vertex counts of all levels), each by the
// wall clock and by this thread's CPU time (cpu_*), and the vertex count after each level (v0, v1, ...).
// Analysis includes building the coarse Mesh (from the twins the collapses kept, no edge sort).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <map>
#include <string>

#include "geoshift/shapes.hpp"
#include "geoshift/wavelet.hpp"

using namespace geoshift;

namespace {

// Value noise on an integer lattice: a hash per lattice point, smoothstep-interpolated.
double lattice(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full ^ seed;
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  return static_cast<double>(h >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

double valueNoise(double x, double y, std::uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  double u = x - fx, v = y - fy;
  u = u * u * (3 - 2 * u);
  v = v * v * (3 - 2 * v);
  const double a = lattice(i, j, seed), b = lattice(i + 1, j, seed), c = lattice(i, j + 1, seed),
               d = lattice(i + 1, j + 1, seed);
  return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
}

// Fractional Brownian motion: octaves of value noise, each twice the frequency and ~half the amplitude.
double fractalHeight(double x, double y) {
  double h = 0, amplitude = 0.08, frequency = 4;
  for (int octave = 0; octave < 9; ++octave) {
    h += amplitude * valueNoise(frequency * x, frequency * y, 1234 + octave);
    amplitude *= 0.5;
    frequency *= 2;
  }
  return h;
}

struct Terrain {
  Mesh mesh;
  AttributeSet attributes;
};

const Terrain& terrain(int side) {
  static std::map<int, Terrain> cache;
  auto it = cache.find(side);
  if (it != cache.end()) return it->second;
  TriangleSoup s = shapes::grid(side, 0.2, 3);
  for (Vec3& p : s.positions) p.z() = fractalHeight(p.x(), p.y());
  Terrain t{buildMesh(s).mesh, {}};
  std::vector<double> vegetation(t.mesh.vertexCount());
  for (int v = 0; v < t.mesh.vertexCount(); ++v)
    vegetation[v] = std::max(0.0, 20 * valueNoise(40 * t.mesh.position(v).x(), 40 * t.mesh.position(v).y(), 99));
  t.attributes = AttributeSet(t.mesh.vertexCount());
  t.attributes.set("vegetation", 1, AttributeKind::Euclidean, std::move(vegetation));
  return cache.emplace(side, std::move(t)).first->second;
}

// CPU time of this thread: on a shared machine the wall clock also counts other processes' turns.
double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void setCounters(benchmark::State& state, const Multiresolution& mr, double seconds, double cpuSeconds) {
  const std::vector<int> counts = mr.vertexCounts();
  double processed = 0;
  for (size_t k = 0; k + 1 < counts.size(); ++k) processed += counts[k];
  const double n = counts.front(), L = mr.levelCount();
  state.counters["us_per_vertex_level"] = 1e6 * seconds / (n * L);
  state.counters["us_per_processed_vertex"] = 1e6 * seconds / processed;
  state.counters["cpu_us_per_vertex_level"] = 1e6 * cpuSeconds / (n * L);
  state.counters["cpu_us_per_processed_vertex"] = 1e6 * cpuSeconds / processed;
  for (size_t k = 0; k < counts.size(); ++k) state.counters["v" + std::to_string(k)] = counts[k];
}

void BM_WaveletAnalysis(benchmark::State& state) {
  const Terrain& t = terrain(static_cast<int>(state.range(0)));
  WaveletOptions o;
  o.levels = static_cast<int>(state.range(1));
  Multiresolution mr;
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = threadSeconds();
    mr = analyze(t.mesh, t.attributes, o);
    cpu = threadSeconds() - cpuStart;
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(mr.coarse.vertexCount());
  }
  setCounters(state, mr, seconds, cpu);
}

void BM_WaveletSynthesis(benchmark::State& state) {
  const Terrain& t = terrain(static_cast<int>(state.range(0)));
  WaveletOptions o;
  o.levels = static_cast<int>(state.range(1));
  const Multiresolution mr = analyze(t.mesh, t.attributes, o);
  const std::vector<double> alpha = {0.5};
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = threadSeconds();
    SynthesisResult r = synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, alpha);
    cpu = threadSeconds() - cpuStart;
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(r.mesh.vertexCount());
  }
  setCounters(state, mr, seconds, cpu);
}

void levelsArgs(benchmark::internal::Benchmark* b) {
  for (int side : {317, 1000})
    for (int L : {2, 4, 6, 8, 10, 12}) b->Args({side, L});
}

}  // namespace

BENCHMARK(BM_WaveletAnalysis)->Apply(levelsArgs)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(false);
BENCHMARK(BM_WaveletSynthesis)->Apply(levelsArgs)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->ReportAggregatesOnly(false);

BENCHMARK_MAIN();

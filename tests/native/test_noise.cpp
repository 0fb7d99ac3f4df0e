// Seeded synthetic noise (docs/algorithms.md#noise-and-error-metrics).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

NoiseOptions options(NoiseDistribution d, NoiseDirection dir, double amount = 0.5,
                     std::uint64_t seed = 1) {
  NoiseOptions o;
  o.amount = amount;
  o.distribution = d;
  o.direction = dir;
  o.seed = seed;
  return o;
}

}  // namespace

TEST_CASE("same seed, same noise; other seed, other noise", "[noise][seed]") {
  const Mesh clean = build(shapes::icosphere(3));
  Mesh a = clean, b = clean, c = clean;
  const auto o = options(NoiseDistribution::Gaussian, NoiseDirection::Random, 0.5, 42);
  const auto da = addNoise(a, o);
  const auto db = addNoise(b, o);
  CHECK(da == db);  // bit-identical
  CHECK(a.positions() == b.positions());
  auto other = o;
  other.seed = 43;
  const auto dc = addNoise(c, other);
  int differ = 0;
  for (size_t v = 0; v < da.size(); ++v) differ += da[v] != dc[v];
  CHECK(differ == static_cast<int>(da.size()));
  for (int v = 0; v < clean.vertexCount(); ++v) {
    CHECK(a.position(v) == clean.position(v) + da[v]);  // the returned displacement is what moved
  }
}

TEST_CASE("the generator is pinned: seed 1 gives the recorded displacements", "[noise][seed]") {
  // Guards the promise that native (libstdc++) and wasm (libc++) builds agree bit for bit: these
  // values come from the raw mt19937_64 stream and our own transforms only (no std distribution,
  // no libm log). If they change, every recorded figure made with a seed changes too. (Changed twice:
  // the three components of a random direction used to be drawn in an unspecified order; and native
  // builds summed 3-vector norms with SSE2 in another order than wasm, a last bit apart.)
  std::mt19937_64 reference;  // C++ [rand.predef]: the 10000th output is fixed by the standard
  reference.discard(9999);
  CHECK(reference() == 9981545732273789042ull);

  Mesh m = build(shapes::icosphere(1));
  NoiseOptions o;
  o.distribution = NoiseDistribution::Gaussian;
  const auto d = addNoise(m, o);
  CHECK(d[0] == Vec3(-0x1.1794815b5352cp-6, -0x1.571e09036fd88p-3, -0x1.b9a15d407fdf4p-4));
  CHECK(d[41] == Vec3(0x1.4fae3b7e534b9p-4, -0x1.440e6dbdc5dc9p-2, -0x1.2362b50455d95p-2));
}

TEST_CASE("Fixed magnitude is amount × AEL for every vertex", "[noise][fixed]") {
  Mesh m = build(shapes::icosphere(3));
  const double ael = averageEdgeLength(m);
  const auto d = addNoise(m, options(NoiseDistribution::Fixed, NoiseDirection::Random, 0.5));
  Vec3 mean = Vec3::Zero();
  for (const Vec3& x : d) {
    CHECK(x.norm() == Approx(0.5 * ael).epsilon(1e-14));
    mean += x.normalized() / d.size();
  }
  // Uniform directions on the sphere: the mean of 642 unit vectors is ~ 1/sqrt(642) ≈ 0.04.
  CHECK(mean.norm() < 0.15);
}

TEST_CASE("Uniform magnitude lies in [0, amount × AEL] with mean half", "[noise][uniform]") {
  Mesh m = build(shapes::icosphere(5));
  const double ael = averageEdgeLength(m);
  const auto d = addNoise(m, options(NoiseDistribution::Uniform, NoiseDirection::Random, 0.5, 9));
  double mean = 0;
  Vec3 direction = Vec3::Zero();
  for (const Vec3& x : d) {
    CHECK(x.norm() <= 0.5 * ael * (1 + 1e-14));
    mean += x.norm() / d.size();
    if (x.norm() > 0) direction += x.normalized() / d.size();
  }
  // 10242 samples of U[0, 1]: standard error of the mean 0.29 / 101 ≈ 0.003.
  CHECK(mean / (0.5 * ael) == Approx(0.5).margin(0.015));
  CHECK(direction.norm() < 0.05);
}

TEST_CASE("Gaussian noise along the normal has std σ and is parallel to it", "[noise][gaussian]") {
  Mesh m = build(shapes::icosphere(5));
  const double ael = averageEdgeLength(m);
  const std::vector<Vec3> normals = vertexNormals(m);
  const double amount = 0.3;
  const auto d = addNoise(m, options(NoiseDistribution::Gaussian, NoiseDirection::Normal, amount, 5));
  double sum = 0, sum2 = 0;
  for (size_t v = 0; v < d.size(); ++v) {
    CHECK(d[v].cross(normals[v]).norm() <= 1e-15 + 1e-12 * d[v].norm());
    const double s = d[v].dot(normals[v]);
    sum += s;
    sum2 += s * s;
  }
  const double n = static_cast<double>(d.size());
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  const double sigma = amount * ael;
  CHECK(std::abs(mean) < 0.05 * sigma);  // standard error σ/101
  CHECK(sd == Approx(sigma).epsilon(0.04));
}

TEST_CASE("isolated vertices are not displaced; bad amounts are refused", "[noise][input]") {
  TriangleSoup soup = shapes::icosphere(1);
  soup.positions.emplace_back(5, 5, 5);
  Mesh m(soup.positions, soup.faces);
  const auto d = addNoise(m);
  CHECK(d.back().isZero(0));
  CHECK(m.positions().back() == Vec3(5, 5, 5));
  CHECK_THROWS_AS(addNoise(m, options(NoiseDistribution::Fixed, NoiseDirection::Random, -1)),
                  InputError);
}

// Taubin λ|μ smoothing (docs/algorithms.md#taubin-smoothing).
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/smoothing.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

double meanRadius(const Mesh& m) {
  double s = 0;
  for (const Vec3& p : m.positions()) s += p.norm();
  return s / m.vertexCount();
}

// RMS deviation of |p| from the sphere's radius: what the noise adds and smoothing removes.
double radialRms(const Mesh& m, double radius) {
  double s = 0;
  for (const Vec3& p : m.positions()) s += (p.norm() - radius) * (p.norm() - radius);
  return std::sqrt(s / m.vertexCount());
}

}  // namespace

TEST_CASE("Taubin keeps a noisy sphere's radius and removes the noise", "[taubin][sphere]") {
  const auto weights = GENERATE(LaplacianWeights::Uniform, LaplacianWeights::Fujiwara,
                                LaplacianWeights::Cotangent);
  Mesh m = build(shapes::icosphere(4));
  NoiseOptions noise;
  noise.amount = 0.2;
  noise.distribution = NoiseDistribution::Gaussian;
  noise.direction = NoiseDirection::Normal;
  addNoise(m, noise);
  const double noisy = radialRms(m, 1.0);
  REQUIRE(noisy > 0.005);

  TaubinOptions options;  // MeshLab's defaults: 10 steps, λ = 0.5, μ = −0.53
  options.weights = weights;
  taubinSmooth(m, options);
  INFO("weights " << static_cast<int>(weights) << ": radial RMS " << noisy << " -> "
                  << radialRms(m, 1.0) << ", mean radius " << meanRadius(m));
  CHECK(std::abs(meanRadius(m) - 1.0) < 0.01);
  CHECK(radialRms(m, meanRadius(m)) < 0.5 * noisy);
}

TEST_CASE("Taubin shrinks a sphere far less than Laplacian smoothing", "[taubin][sphere]") {
  Mesh taubin = build(shapes::icosphere(3));
  Mesh laplace = taubin;
  taubinSmooth(taubin, {50, 0.5, -0.53, LaplacianWeights::Uniform});
  // Pure umbrella-Laplacian smoothing with the same λ and the same number of steps (100: Taubin
  // makes two per iteration). The API has no such mode, so it is written out here.
  for (int i = 0; i < 100; ++i) {
    const Mesh before = laplace;
    for (int v = 0; v < laplace.vertexCount(); ++v) {
      Vec3 avg = Vec3::Zero();
      const auto nb = before.neighbors(v);
      for (int j : nb) avg += before.position(j);
      laplace.position(v) = before.position(v) + 0.5 * (avg / nb.size() - before.position(v));
    }
  }
  CHECK(1.0 - meanRadius(taubin) < 0.2 * (1.0 - meanRadius(laplace)));
}

TEST_CASE("Taubin keeps a jittered plane planar", "[taubin][plane]") {
  const auto weights = GENERATE(LaplacianWeights::Uniform, LaplacianWeights::Fujiwara,
                                LaplacianWeights::Cotangent);
  Mesh m = build(shapes::grid(60, 0.3, 11));
  const Mesh before = m;
  taubinSmooth(m, {10, 0.5, -0.53, weights});
  double moved = 0;
  for (int v = 0; v < m.vertexCount(); ++v) {
    CHECK(m.position(v).z() == 0.0);
    moved = std::max(moved, (m.position(v) - before.position(v)).norm());
  }
  // The 1D boundary Laplacian keeps a border vertex on its border line until the corner, which
  // moves diagonally inward, drags its neighbours along: check the middle of each side.
  const int n = 60;  // 10 iterations = 20 Laplacian steps reach 20 vertices from a corner
  for (int i = 22; i < n - 22; ++i) {
    CHECK(m.position(i).y() == Approx(0.0).margin(1e-12));                    // bottom side
    CHECK(m.position(i * n).x() == Approx(0.0).margin(1e-12));                // left side
  }
  // No triangle folds over with the umbrella and Fujiwara weights. (Cotangent weights on this
  // strongly jittered grid fold two slivers: their μ step amplifies the large cotangents.)
  if (weights != LaplacianWeights::Cotangent) {
    for (const Face& f : m.faces()) {
      const Vec3 e1 = m.position(f[1]) - m.position(f[0]);
      const Vec3 e2 = m.position(f[2]) - m.position(f[0]);
      CHECK(e1.cross(e2).z() > 0);
    }
  }
  CHECK(moved > 1e-3);  // it did smooth the jitter
}

TEST_CASE("isolated vertices do not move", "[taubin][isolated]") {
  TriangleSoup soup = shapes::icosphere(2);
  soup.positions.emplace_back(3, 3, 3);
  const Mesh original(soup.positions, soup.faces);
  Mesh m = original;
  const int isolated = m.vertexCount() - 1;
  REQUIRE(m.isIsolated(isolated));
  taubinSmooth(m, {10, 0.5, -0.53, LaplacianWeights::Cotangent});
  CHECK(m.position(isolated) == Vec3(3, 3, 3));
  CHECK((m.position(0) - original.position(0)).norm() > 0);
}

TEST_CASE("Taubin rejects invalid options", "[taubin][options]") {
  Mesh m = build(shapes::icosphere(1));
  CHECK_THROWS_AS(taubinSmooth(m, {-1, 0.5, -0.53}), InputError);
  CHECK_THROWS_AS(taubinSmooth(m, {10, 0.0, -0.53}), InputError);
  CHECK_THROWS_AS(taubinSmooth(m, {10, -0.5, -0.53}), InputError);
  CHECK_THROWS_AS(taubinSmooth(m, {10, 0.5, -0.5}), InputError);  // μ = −λ: no pass band
  CHECK_THROWS_AS(taubinSmooth(m, {10, 0.5, 0.2}), InputError);
  CHECK_THROWS_AS(taubinSmooth(m, {10, std::nan(""), -0.53}), InputError);
  CHECK_THROWS_WITH(taubinSmooth(m, {10, 0.5, -0.1}), Catch::Contains("mu"));
  const Mesh untouched = build(shapes::icosphere(1));
  CHECK(m.positions() == untouched.positions());
  taubinSmooth(m, {0, 0.5, -0.53});
  CHECK(m.positions() == untouched.positions());
}

TEST_CASE("Taubin reports progress and honours cancel", "[taubin][progress]") {
  Mesh m = build(shapes::icosphere(2));
  const Mesh original = m;
  int calls = 0;
  double last = -1;
  Progress progress;
  progress.report = [&](double fraction, std::string_view) {
    CHECK(fraction >= last);
    last = fraction;
    ++calls;
  };
  taubinSmooth(m, {7, 0.5, -0.53}, progress);
  CHECK(calls >= 7);
  CHECK(last == 1.0);

  std::atomic<bool> cancel{false};
  Mesh c = original;
  Progress cancelling;
  cancelling.cancel = &cancel;
  cancelling.report = [&](double fraction, std::string_view) {
    if (fraction > 0.25) cancel = true;  // raised mid-way, as another thread would
  };
  CHECK_THROWS_AS(taubinSmooth(c, {10, 0.5, -0.53}, cancelling), Cancelled);
  CHECK(c.positions() == original.positions());  // nothing written
}

TEST_CASE("Taubin gives the same positions on any number of threads", "[taubin][threads]") {
  // Each half-step writes every vertex from the previous positions alone, so the split of the
  // vertices among threads cannot change a bit; a shared buffer written in place would.
  const auto weights = GENERATE(LaplacianWeights::Uniform, LaplacianWeights::Fujiwara,
                                LaplacianWeights::Cotangent);
  // A boundary (1D stencils) and 8k vertices: 9 chunks of the loop's 1024, shared among the threads.
  Mesh noisy = build(shapes::grid(90, 0.3));
  NoiseOptions noise;
  noise.amount = 0.3;
  addNoise(noisy, noise);
  TaubinOptions options{12, 0.5, -0.53, weights};
  options.parallel.threads = 1;
  Mesh serial = noisy;
  taubinSmooth(serial, options);
  REQUIRE(serial.positions() != noisy.positions());
  for (int threads : {2, 3, 4}) {
    options.parallel.threads = threads;
    Mesh m = noisy;
    taubinSmooth(m, options);
    INFO("weights " << static_cast<int>(weights) << ", " << threads << " threads");
    CHECK(m.positions() == serial.positions());
  }
}

TEST_CASE("uniform Taubin is the umbrella operator written out, to the bit", "[taubin][reference]") {
  // A plain reference of Taubin (1995) with uniform weights: each half-step moves every vertex by
  // factor × the mean of (x_j − x_v) over its neighbours, taken around it in the mesh's order; a
  // boundary vertex averages its two neighbours along the boundary. The filter's own loop is
  // written for speed (docs/denoising.md#speed-and-memory); it must give these very bits.
  const bool open = GENERATE(false, true);
  Mesh noisy = open ? build(shapes::grid(40, 0.3, 5)) : build(shapes::icosphere(3));
  NoiseOptions noise;
  noise.amount = 0.4;
  noise.seed = 9;
  addNoise(noisy, noise);
  // Boundary edges: those of a single face.
  std::map<std::pair<int, int>, int> edgeFaces;
  for (const Face& f : noisy.faces())
    for (int k = 0; k < 3; ++k) ++edgeFaces[std::minmax(f[k], f[(k + 1) % 3])];
  std::vector<std::vector<int>> boundaryNeighbors(noisy.vertexCount());
  for (const auto& [edge, faces] : edgeFaces) {
    if (faces != 1) continue;
    boundaryNeighbors[edge.first].push_back(edge.second);
    boundaryNeighbors[edge.second].push_back(edge.first);
  }
  std::vector<Vec3> x = noisy.positions();
  const int steps = 4;
  for (int it = 0; it < steps; ++it) {
    for (double factor : {0.5, -0.53}) {
      std::vector<Vec3> next(x.size());
      for (int v = 0; v < noisy.vertexCount(); ++v) {
        std::vector<int> ring;
        if (noisy.isBoundaryVertex(v)) {
          ring = boundaryNeighbors[v];
          REQUIRE(ring.size() == 2);
        } else {
          noisy.forEachOutgoing(v, [&](int h) { ring.push_back(noisy.head(h)); });
        }
        Vec3 sum = Vec3::Zero();
        for (int j : ring) sum += x[j] - x[v];
        next[v] = x[v] + factor * (sum / static_cast<double>(ring.size()));
      }
      x = next;
    }
  }
  Mesh m = noisy;
  taubinSmooth(m, {steps, 0.5, -0.53, LaplacianWeights::Uniform});
  REQUIRE(m.positions() != noisy.positions());
  int differing = 0;
  for (int v = 0; v < m.vertexCount(); ++v) differing += m.position(v) != x[v];
  CHECK(differing == 0);
}

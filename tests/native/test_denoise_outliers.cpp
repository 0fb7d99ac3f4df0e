// The correction for impulsive noise (core/src/denoise_detail.hpp, docs/denoising.md#impulsive-noise),
// white-box: on a flat grid whose smoothed copy lost a uniform detail, an outlier is brought back to
// the detail's level (not to the smoothed copy's), the other vertices keep the input's positions,
// and a vertex without a normal keeps the smoothed position.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "denoise_detail.hpp"
#include "geoshift/shapes.hpp"
#include "denoise_support.hpp"

using namespace geoshift;
using namespace geoshift::denoise_detail;
using namespace geoshift::test;

TEST_CASE("an outlier is corrected to the level of its trusted neighbours", "[denoise][impulsive]") {
  const Mesh grid = buildMesh(shapes::grid(9)).mesh;  // z = 0, spacing 1/8
  const int n = grid.vertexCount();
  const int outlier = 4 * 9 + 4, neighbor = outlier + 1, bare = 0;
  const double detail = 0.01, spike = 0.5, tau = 0.05;

  // The input: the grid lifted by `detail`, one vertex further by `spike`; the smoothed copy: the
  // flat grid. Every vertex but `bare` has the normal +z.
  std::vector<Vec3> input(n), smoothed(n), normals(n, Vec3(0, 0, 1));
  for (int v = 0; v < n; ++v) {
    smoothed[v] = grid.position(v);
    input[v] = grid.position(v) + Vec3(0, 0, detail + (v == outlier ? spike : 0));
  }
  normals[bare] = Vec3::Zero();

  std::vector<Vec3> x = smoothed;
  correctOutliers(grid, input, x, normals, tau);
  const double w = 1 - tau * tau / ((detail + spike) * (detail + spike));
  for (int v = 0; v < n; ++v) {
    INFO("vertex " << v);
    if (v == bare) {
      REQUIRE(x[v] == smoothed[v]);
    } else if (v == outlier) {
      // Pulled back by w of the spike alone: the detail its neighbours kept is given back.
      REQUIRE(x[v].x() == Approx(input[v].x()));
      REQUIRE(x[v].y() == Approx(input[v].y()));
      REQUIRE(x[v].z() == Approx(detail + spike - w * spike).margin(1e-12));
    } else {
      REQUIRE(x[v] == input[v]);
    }
  }
  // The garrote alone would have taken the detail too.
  REQUIRE(std::abs(x[outlier].z() - (detail + spike - w * (detail + spike))) > 0.5 * detail);

  SECTION("a neighbouring outlier is trusted by 1 − its weight") {
    input[neighbor].z() += spike;
    std::vector<Vec3> y = smoothed;
    correctOutliers(grid, input, y, normals, tau);
    const std::vector<int> ring = grid.neighbors(outlier);
    REQUIRE(std::count(ring.begin(), ring.end(), neighbor) == 1);
    // The mean of input − smoothed over the ring: detail everywhere, detail + spike at `neighbor`
    // with weight 1 − w.
    const double trust = (ring.size() - 1) + (1 - w);
    const double taken = ((ring.size() - 1) * detail + (1 - w) * (detail + spike)) / trust;
    REQUIRE(y[outlier].z() == Approx(detail + spike + w * (taken - detail - spike)).margin(1e-12));
    REQUIRE(y[outlier].z() > x[outlier].z());
  }
}

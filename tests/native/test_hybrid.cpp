// The hybrid filter (Algorithm 2): wavelet analysis, mean shift on the coarse mesh, synthesis.
#include <catch2/catch.hpp>

#include <random>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/hybrid.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

AttributeSet stepColors(const Mesh& mesh, double sigma) {
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> rgb;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const bool up = mesh.position(v).z() > 0;
    for (double c : {up ? 1.0 : 0.0, 0.0, up ? 0.0 : 1.0}) rgb.push_back(c + noise(rng));
  }
  AttributeSet set(mesh.vertexCount());
  set.set("COLOR", 3, AttributeKind::Euclidean, rgb);
  return set;
}

// Over the vertices farther than `band` from the step at z = 0.
double regionVariance(const Mesh& mesh, const std::vector<double>& rgb, bool up, double band = 0) {
  double s[3] = {0, 0, 0}, q[3] = {0, 0, 0};
  int n = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    if ((mesh.position(v).z() > 0) != up || std::abs(mesh.position(v).z()) < band) continue;
    ++n;
    for (int c = 0; c < 3; ++c) {
      s[c] += rgb[3 * v + c];
      q[c] += rgb[3 * v + c] * rgb[3 * v + c];
    }
  }
  double total = 0;
  for (int c = 0; c < 3; ++c) total += q[c] / n - (s[c] / n) * (s[c] / n);
  return total;
}

}  // namespace

TEST_CASE("hybrid filter with no levels is the mean shift itself", "[hybrid]") {
  const Mesh mesh = build(shapes::icosphere(3));
  const AttributeSet colors = stepColors(mesh, 0.05);
  MeanShiftOptions o;
  o.rangeBandwidth = 0.3;
  const HybridResult h = hybridMeanShift(mesh, colors, o, HybridOptions{});
  const MeanShiftResult direct = meanShift(mesh, colors, o);
  REQUIRE(h.signal.get("COLOR").values == direct.signal.get("COLOR").values);
  REQUIRE(h.positions == mesh.positions());
}

TEST_CASE("hybrid filter: a constant signal with alpha 1 comes back unchanged", "[hybrid]") {
  const Mesh mesh = build(shapes::icosphere(4));
  AttributeSet set(mesh.vertexCount());
  set.set("S", 1, AttributeKind::Euclidean, std::vector<double>(mesh.vertexCount(), 2.5));
  HybridOptions h;
  h.levels = 3;
  h.alpha = {1};
  const HybridResult r = hybridMeanShift(mesh, set, MeanShiftOptions{}, h);
  REQUIRE(r.vertexCounts.size() == 4);
  REQUIRE(r.vertexCounts.back() < mesh.vertexCount() / 2);
  for (double x : r.signal.get("S").values) REQUIRE(x == Approx(2.5).margin(1e-9));
}

TEST_CASE("hybrid filter smooths a noisy step on far fewer vertices and keeps the edge", "[hybrid]") {
  const Mesh mesh = build(shapes::icosphere(5));
  const double ael = averageEdgeLength(mesh);
  const AttributeSet noisy = stepColors(mesh, 0.08);
  MeanShiftOptions o;
  o.rangeBandwidth = 0.3;
  o.segments = true;
  HybridOptions h;
  h.levels = 2;
  h.alpha = {0};
  const HybridResult r = hybridMeanShift(mesh, noisy, o, h);
  const std::vector<double>& out = r.signal.get("COLOR").values;
  INFO("vertices per level " << r.vertexCounts[0] << " " << r.vertexCounts[1] << " " << r.vertexCounts[2]);
  REQUIRE(r.vertexCounts.back() < 0.65 * mesh.vertexCount());
  // Away from the step: dropping the details blends the fine vertices next to it (checked below).
  for (bool up : {true, false})
    REQUIRE(regionVariance(mesh, out, up, 2 * ael) * 10 <= regionVariance(mesh, noisy.get("COLOR").values, up, 2 * ael));
  // The edge moves by at most the coarse mesh's spacing: two fine edges.
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const bool red = out[3 * v] > out[3 * v + 2];
    if (red != (mesh.position(v).z() > 0)) REQUIRE(std::abs(mesh.position(v).z()) < 2 * ael);
  }
  REQUIRE(r.segment.size() == static_cast<size_t>(mesh.vertexCount()));
  for (int s : r.segment) REQUIRE((s >= 0 && s < r.segmentCount));
  REQUIRE(r.positions == mesh.positions());
}

TEST_CASE("hybrid filter rejects bad levels and gains", "[hybrid]") {
  const Mesh mesh = build(shapes::icosphere(3));
  const AttributeSet colors = stepColors(mesh, 0.05);
  HybridOptions h;
  h.levels = -1;
  REQUIRE_THROWS_AS(hybridMeanShift(mesh, colors, MeanShiftOptions{}, h), InputError);
  h.levels = 2;
  h.alpha = {0, 0, 0};
  REQUIRE_THROWS_AS(hybridMeanShift(mesh, colors, MeanShiftOptions{}, h), InputError);
}

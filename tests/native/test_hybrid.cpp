// The hybrid filter (Algorithm 2): wavelet analysis, mean shift on the coarse mesh, synthesis.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/hybrid.hpp"
#include "geoshift/presets.hpp"
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

// Issue 30: with the curvature preset's two levels (details dropped) the absolute curvature of a
// CAD part came back with negative values and a saw tooth along every crease. A closed box has the
// same field in its simplest form: one constant value along each crease (away from the corners),
// zero on the faces, larger at the corners.
TEST_CASE("hybrid curvature filter on a box: within the raw field's range, no spikes along the creases", "[hybrid]") {
  const Mesh mesh = build(shapes::box(16, 16, 16));
  const std::vector<double> raw = curvatures(mesh).get(CurvatureKind::Absolute);
  AttributeSet set(mesh.vertexCount());
  set.set("_CURVATURE", 1, AttributeKind::Euclidean, raw);
  const FilterPreset& preset = filterPreset("curvature-ms");
  MeanShiftOptions o = preset.options;
  HybridOptions h;
  h.levels = preset.levels;
  h.alpha = {preset.detailGain};
  REQUIRE(h.levels == 2);
  REQUIRE(h.alpha[0] == 0);
  const HybridResult r = hybridMeanShift(mesh, set, o, h);
  REQUIRE(r.vertexCounts.back() < 0.6 * mesh.vertexCount());
  const std::vector<double>& out = r.signal.get("_CURVATURE").values;
  const auto [lo, hi] = std::minmax_element(raw.begin(), raw.end());
  // The mean shift itself reads values at points of the surface through approximate charts, a few
  // 1e-9 of the range outside it at most (a flat face read -5.6e-8 of a field up to 37).
  const double tolerance = 1e-6 * *hi;
  // On the crease away from the corners the raw field is one value; the flat faces' is zero.
  double crease = -1;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    INFO("vertex " << v << " at " << mesh.position(v).transpose() << ": raw " << raw[v] << ", filtered " << out[v]);
    REQUIRE(out[v] >= *lo - tolerance);
    REQUIRE(out[v] <= *hi + tolerance);
    const Vec3 p = mesh.position(v);
    int onFace = 0;
    double inner = 0;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(std::abs(p[k]) - 0.5) < 1e-9) ++onFace;
      else inner = std::max(inner, std::abs(p[k]));
    }
    if (onFace == 2 && inner < 0.35) {
      if (crease < 0) crease = raw[v];
      REQUIRE(raw[v] == Approx(crease).epsilon(1e-9));
      // The old synthesis dropped odd crease vertices to a quarter of this (5.3 of 22.6).
      REQUIRE(out[v] == Approx(crease).epsilon(0.01));
    }
    // Two fine edges (1/16 each) or more from every crease: the faces stay flat.
    if (onFace == 1 && inner < 0.5 - 2.0 / 16) REQUIRE(std::abs(out[v]) <= 0.01 * crease);
  }
  REQUIRE(crease > 0);
}

TEST_CASE("hybrid filter with details: alpha 1 gives a step back when the mean shift keeps it", "[hybrid]") {
  const Mesh mesh = build(shapes::icosphere(4));
  AttributeSet set(mesh.vertexCount());
  std::vector<double> step;
  for (int v = 0; v < mesh.vertexCount(); ++v) step.push_back(mesh.position(v).z() > 0.1 ? 3.0 : -1.0);
  set.set("S", 1, AttributeKind::Euclidean, step);
  MeanShiftOptions o;
  o.rangeBandwidth = 0.05;  // the two values are 80 h_r apart: each side is averaged with itself only
  HybridOptions h;
  h.levels = 2;
  h.alpha = {1};
  const HybridResult r = hybridMeanShift(mesh, set, o, h);
  const std::vector<double>& out = r.signal.get("S").values;
  for (int v = 0; v < mesh.vertexCount(); ++v) REQUIRE(out[v] == Approx(step[v]).margin(1e-9));
}

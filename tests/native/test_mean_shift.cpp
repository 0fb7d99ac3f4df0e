// Riemannian mean shift (docs/algorithms.md#mean-shift; docs/testing.md#what-tests-assert): fixed points, the h_r → ∞ limit against a
// brute-force geodesic Gaussian, a noisy two-region step, blurring passes, threads, cancel.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <random>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

// The samples' weights of the filter: a third of the adjacent faces' areas.
std::vector<double> vertexAreas(const Mesh& mesh) {
  std::vector<double> area(mesh.vertexCount(), 0.0);
  const std::vector<double> faces = faceAreas(mesh);
  for (int f = 0; f < mesh.faceCount(); ++f)
    for (int v : mesh.face(f)) area[v] += faces[f] / 3;
  return area;
}

AttributeSet colors(const std::vector<double>& rgb) {
  AttributeSet set(static_cast<int>(rgb.size() / 3));
  set.set("COLOR", 3, AttributeKind::Euclidean, rgb);
  return set;
}

// Red above z = 0, blue below, plus Gaussian noise of σ per channel (fixed seed).
std::vector<double> stepColors(const Mesh& mesh, double sigma, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> rgb;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const bool up = mesh.position(v).z() > 0;
    for (double c : {up ? 1.0 : 0.0, 0.0, up ? 0.0 : 1.0}) rgb.push_back(c + noise(rng));
  }
  return rgb;
}

double variance(const std::vector<double>& rgb, const Mesh& mesh, bool up) {
  double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
  int n = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    if ((mesh.position(v).z() > 0) != up) continue;
    ++n;
    for (int c = 0; c < 3; ++c) {
      sum[c] += rgb[3 * v + c];
      sq[c] += rgb[3 * v + c] * rgb[3 * v + c];
    }
  }
  double total = 0;
  for (int c = 0; c < 3; ++c) total += sq[c] / n - (sum[c] / n) * (sum[c] / n);
  return total;
}

double totalVariation(const Mesh& mesh, const std::vector<double>& rgb) {
  double tv = 0;
  for (int h = 0; h < 3 * mesh.faceCount(); ++h) {
    if (mesh.twin(h) >= 0 && mesh.twin(h) < h) continue;  // each edge once
    const int a = mesh.tail(h), b = mesh.head(h);
    double d2 = 0;
    for (int c = 0; c < 3; ++c) d2 += (rgb[3 * a + c] - rgb[3 * b + c]) * (rgb[3 * a + c] - rgb[3 * b + c]);
    tv += std::sqrt(d2);
  }
  return tv;
}

}  // namespace

TEST_CASE("a constant signal is a fixed point of mean shift and of blurring passes", "[meanshift]") {
  const Mesh mesh = build(shapes::icosphere(3));
  const std::vector<double> rgb(3 * mesh.vertexCount(), 0.25);
  for (int passes : {1, 3}) {
    MeanShiftOptions o;
    o.passes = passes;
    o.spatialBandwidth = 2;
    const MeanShiftResult r = meanShift(mesh, colors(rgb), o);
    const Attribute& out = r.signal.get("COLOR");
    for (double x : out.values) REQUIRE(x == Approx(0.25).margin(1e-12));
    REQUIRE(r.convergedFraction == 1.0);
  }
}

// With h_r -> infinity, one joint step from each vertex is the Gaussian average of the signal with
// geodesic distances, area-weighted and truncated at the radius: the largest difference between the
// filter and that average computed by brute force with `distance` (every `stride`-th vertex).
template <class Distance>
double worstAgainstGaussian(const Mesh& mesh, const std::vector<double>& signal, double hsAel, double radiusAel,
                            int stride, Distance distance, bool singlePrecision = true) {
  const SurfaceGeometry geometry(mesh);
  AttributeSet set(mesh.vertexCount());
  set.set("S", 1, AttributeKind::Euclidean, signal);
  MeanShiftOptions o;
  o.spatialBandwidth = hsAel;
  o.radius = radiusAel;
  o.rangeBandwidth = 1e9;
  o.maxIterations = 1;
  o.rangeUpdate = RangeUpdate::Joint;
  o.tuning.singlePrecisionKernel = singlePrecision;
  const std::vector<double> filtered = meanShift(geometry, set, o).signal.get("S").values;
  const std::vector<double> area = vertexAreas(mesh);
  const double hs = hsAel * geometry.averageEdgeLength(), radius = radiusAel * geometry.averageEdgeLength();
  double worst = 0;
  for (int i = 0; i < mesh.vertexCount(); i += stride) {
    double sw = 0, sf = 0;
    for (int j = 0; j < mesh.vertexCount(); ++j) {
      const double d = distance(mesh.position(i), mesh.position(j));
      if (d > radius) continue;
      const double w = area[j] * std::exp(-d * d / (2 * hs * hs));
      sw += w;
      sf += w * signal[j];
    }
    worst = std::max(worst, std::abs(filtered[i] - sf / sw));
  }
  return worst;
}

TEST_CASE("with h_r -> infinity one joint step is the geodesic Gaussian average", "[meanshift]") {
  // On a jittered plane the log map is exact, so the brute-force reference uses straight-line
  // distances in the plane.
  const Mesh mesh = build(shapes::grid(21, 0.3));
  std::vector<double> signal(mesh.vertexCount());
  for (int v = 0; v < mesh.vertexCount(); ++v) signal[v] = std::sin(9 * mesh.position(v).x()) + mesh.position(v).y();
  const auto straight = [](const Vec3& a, const Vec3& b) { return (a - b).norm(); };
  REQUIRE(worstAgainstGaussian(mesh, signal, 1.5, 4, 1, straight, false) < 1e-9);
  // Single-precision weights (the default) are within ~1e-7 relative: so is the average.
  REQUIRE(worstAgainstGaussian(mesh, signal, 1.5, 4, 1, straight, true) < 1e-6);
}

TEST_CASE("with h_r -> infinity one joint step matches great-circle Gaussian weights on a sphere", "[meanshift]") {
  const Mesh mesh = build(shapes::icosphere(4));
  std::vector<double> signal(mesh.vertexCount());
  for (int v = 0; v < mesh.vertexCount(); ++v) signal[v] = mesh.position(v).x() * mesh.position(v).y() * 4;
  const auto greatCircle = [](const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)); };
  // DGPC distances are within ~2e-3 of great circles at this resolution (test_logmap); a vertex
  // near the truncation radius may fall on either side of it, which moves the mean by little.
  REQUIRE(worstAgainstGaussian(mesh, signal, 2, 5, 7, greatCircle) < 2e-3);
}

TEST_CASE("a noisy two-region step: regions go flat, the edge stays, two segments", "[meanshift]") {
  const Mesh mesh = build(shapes::icosphere(4));
  const SurfaceGeometry geometry(mesh);
  const double ael = geometry.averageEdgeLength();
  const std::vector<double> noisy = stepColors(mesh, 0.08);
  const auto edgeKept = [&](const std::vector<double>& out) {
    // Every vertex whose filtered color sides with the other region lies within an edge of z = 0.
    for (int v = 0; v < mesh.vertexCount(); ++v) {
      const bool red = out[3 * v] > out[3 * v + 2];
      if (red != (mesh.position(v).z() > 0)) REQUIRE(std::abs(mesh.position(v).z()) < ael);
    }
  };
  MeanShiftOptions o;
  o.spatialBandwidth = 3;
  o.rangeBandwidth = 0.3;
  o.segments = true;
  SECTION("joint range update (the default)") {
    REQUIRE(o.rangeUpdate == RangeUpdate::Joint);
    const MeanShiftResult r = meanShift(geometry, colors(noisy), o);
    const std::vector<double>& out = r.signal.get("COLOR").values;
    for (bool up : {true, false}) REQUIRE(variance(out, mesh, up) * 10 <= variance(noisy, mesh, up));
    edgeKept(out);
    REQUIRE(r.convergedFraction > 0.99);
    REQUIRE(r.segmentCount == 2);
    // The segments are the two regions, up to vertices on the edge.
    for (int v = 0; v < mesh.vertexCount(); ++v)
      if ((r.segment[v] == r.segment[0]) != ((mesh.position(v).z() > 0) == (mesh.position(0).z() > 0)))
        REQUIRE(std::abs(mesh.position(v).z()) < ael);
  }
  SECTION("sampled range update (the paper)") {
    // The paper's iterate reads the signal where it stands: on an evenly sampled surface the
    // spatial density is flat, the iterate barely moves, and the output stays close to a sample of
    // the noisy signal (it smooths only by interpolating within a face). It converges, keeps the
    // edge and does not add noise.
    o.rangeUpdate = RangeUpdate::Sampled;
    const MeanShiftResult r = meanShift(geometry, colors(noisy), o);
    const std::vector<double>& out = r.signal.get("COLOR").values;
    for (bool up : {true, false}) REQUIRE(variance(out, mesh, up) <= variance(noisy, mesh, up));
    edgeKept(out);
    REQUIRE(r.convergedFraction > 0.99);
  }
}

TEST_CASE("blurring passes never increase the total variation", "[meanshift]") {
  const Mesh mesh = build(shapes::icosphere(3));
  const SurfaceGeometry geometry(mesh);
  std::vector<double> rgb = stepColors(mesh, 0.08, 11);
  MeanShiftOptions o;
  o.spatialBandwidth = 2;
  o.rangeBandwidth = 0.3;
  o.maxIterations = 5;
  double tv = totalVariation(mesh, rgb);
  for (int pass = 0; pass < 6; ++pass) {
    rgb = meanShift(geometry, colors(rgb), o).signal.get("COLOR").values;
    const double next = totalVariation(mesh, rgb);
    REQUIRE(next <= tv * (1 + 1e-12));
    tv = next;
  }
  // And passes = N is N single passes.
  o.passes = 6;
  const std::vector<double> once = meanShift(geometry, colors(stepColors(mesh, 0.08, 11)), o).signal.get("COLOR").values;
  REQUIRE(once == rgb);
}

TEST_CASE("results do not depend on the thread count", "[meanshift]") {
  const Mesh mesh = build(shapes::icosphere(4));
  const SurfaceGeometry geometry(mesh);
  const AttributeSet noisy = colors(stepColors(mesh, 0.08, 3));
  MeanShiftOptions o;
  o.spatialBandwidth = 2;
  o.rangeBandwidth = 0.3;
  o.passes = 2;
  o.segments = true;
  o.parallel.threads = 1;
  const MeanShiftResult one = meanShift(geometry, noisy, o);
  for (int threads : {2, 4}) {
    o.parallel.threads = threads;
    o.parallel.chunk = 3;  // many hand-outs, interleaved differently each run
    const MeanShiftResult many = meanShift(geometry, noisy, o);
    REQUIRE(many.signal.get("COLOR").values == one.signal.get("COLOR").values);
    REQUIRE(many.iterations == one.iterations);
    REQUIRE(many.segment == one.segment);
  }
}

TEST_CASE("reused charts equal exact charts on a plane", "[meanshift]") {
  const Mesh mesh = build(shapes::grid(25, 0.3));
  const SurfaceGeometry geometry(mesh);
  std::vector<double> rgb;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vec3 p = mesh.position(v);
    for (double c : {p.x() > 0.5 ? 0.9 : 0.1, p.y(), 0.5}) rgb.push_back(c);
  }
  MeanShiftOptions o;
  o.spatialBandwidth = 2;
  o.rangeBandwidth = 0.2;
  const MeanShiftResult reused = meanShift(geometry, colors(rgb), o);
  o.tuning.chartDistortion = 0;  // cubes of side h_s only
  const MeanShiftResult unmerged = meanShift(geometry, colors(rgb), o);
  o.tuning.exactCharts = true;
  const MeanShiftResult exact = meanShift(geometry, colors(rgb), o);
  // The plane is flat: cubes merge into fewer, wider groups (at most 200 vertices each), and
  // their charts are exact all the same.
  CHECK(reused.diagnostics.startCharts < unmerged.diagnostics.startCharts / 4);
  CHECK(reused.diagnostics.startCharts * 200 >= mesh.vertexCount());
  CHECK(exact.diagnostics.startCharts == 0);
  const auto& b = exact.signal.get("COLOR").values;
  for (const MeanShiftResult* r : {&reused, &unmerged}) {
    const auto& a = r->signal.get("COLOR").values;
    double worst = 0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    REQUIRE(worst < 1e-6);
  }
}

TEST_CASE("start charts are shared over wider cubes only where the surface is flat", "[meanshift]") {
  // A unit sphere (K = 1) at 2,562 vertices is too curved for wider cubes at h_s = 2 AEL: the same
  // groups, the same bits. A cylinder is intrinsically flat (K = 0, and charts are exact on it up
  // to its rims) however curved it looks: its cubes merge.
  MeanShiftOptions o;
  o.spatialBandwidth = 2;
  o.rangeBandwidth = 0.2;
  const Mesh sphere = build(shapes::icosphere(4));
  const AttributeSet noisy = colors(stepColors(sphere, 0.08, 5));
  const MeanShiftResult merged = meanShift(sphere, noisy, o);
  o.tuning.chartDistortion = 0;
  const MeanShiftResult unmerged = meanShift(sphere, noisy, o);
  CHECK(merged.diagnostics.startCharts == unmerged.diagnostics.startCharts);
  REQUIRE(merged.signal.get("COLOR").values == unmerged.signal.get("COLOR").values);

  const Mesh tube = build(shapes::cylinder(64, 40, 1.0, 4.0));
  const AttributeSet tubeColors = colors(stepColors(tube, 0.08, 5));
  const MeanShiftResult tubeUnmerged = meanShift(tube, tubeColors, o);
  o.tuning.chartDistortion = 0.1;
  const MeanShiftResult tubeMerged = meanShift(tube, tubeColors, o);
  CHECK(tubeMerged.diagnostics.startCharts < tubeUnmerged.diagnostics.startCharts / 2);
}

TEST_CASE("single-precision kernel weights agree with double precision on a curved surface", "[meanshift]") {
  // The three specialised loops: colors (3 dims) and a scalar far from 0 (1 dim, Gaussian range),
  // noisy normals (normal similarity); mean shift and blurring passes, sampled and joint updates.
  const Mesh mesh = build(shapes::icosphere(4));
  const SurfaceGeometry geometry(mesh);
  const std::vector<double> rgb = stepColors(mesh, 0.08, 5);
  std::vector<double> height, noisyNormals;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    height.push_back(1000 + (mesh.position(v).z() > 0 ? 20 : 2) + 3 * noise(rng));  // meters above sea level
    const Vec3 n = (mesh.position(v).normalized() + 0.2 * Vec3(noise(rng), noise(rng), noise(rng))).normalized();
    noisyNormals.insert(noisyNormals.end(), {n.x(), n.y(), n.z()});
  }
  AttributeSet scalar(mesh.vertexCount()), normals(mesh.vertexCount());
  scalar.set("H", 1, AttributeKind::Euclidean, height);
  normals.set("N", 3, AttributeKind::UnitVector, noisyNormals);
  struct Case {
    const AttributeSet* signal;
    const char* name;
    double hr, scale;  // the range bandwidth and the scale differences are judged on
    RangeKernel kernel;
    RangeUpdate update;
    int passes;
  };
  const AttributeSet color = colors(rgb);
  for (const Case& c : {Case{&color, "COLOR", 0.3, 1, RangeKernel::Gaussian, RangeUpdate::Joint, 1},
                        Case{&color, "COLOR", 0.3, 1, RangeKernel::Gaussian, RangeUpdate::Sampled, 3},
                        Case{&scalar, "H", 4, 18, RangeKernel::Gaussian, RangeUpdate::Joint, 1},
                        Case{&normals, "N", 0.45, 1, RangeKernel::NormalSimilarity, RangeUpdate::Sampled, 1}}) {
    MeanShiftOptions o;
    o.channels = {{c.name, c.hr, c.kernel}};
    o.spatialBandwidth = 2;
    o.rangeUpdate = c.update;
    o.passes = c.passes;
    o.epsilon = 0.05;
    o.tuning.singlePrecisionKernel = false;
    const MeanShiftResult twice = meanShift(geometry, *c.signal, o);
    o.tuning.singlePrecisionKernel = true;
    const MeanShiftResult once = meanShift(geometry, *c.signal, o);
    const std::vector<double>& a = twice.signal.get(c.name).values;
    const std::vector<double>& b = once.signal.get(c.name).values;
    double moved = 0;
    std::vector<double> diff;
    for (size_t i = 0; i < a.size(); ++i) {
      diff.push_back(std::abs(a[i] - b[i]));
      moved = std::max(moved, std::abs(a[i] - c.signal->get(c.name).values[i]));
    }
    std::sort(diff.begin(), diff.end());
    const double worst = diff.back(), p99 = diff[diff.size() * 99 / 100];
    INFO(c.name << " passes " << c.passes << ": differences p99 " << p99 << ", worst " << worst << "; largest change "
                << moved);
    REQUIRE(moved > 0.05 * c.scale);  // the filter did something
    // Weights within ~1e-7 move almost every mode by as little. A mode where the density is nearly
    // flat moves more (seen: 2.4e-4 on one of 7,686 normal rows, a 0.014° turn).
    REQUIRE(p99 < 1e-6 * c.scale);
    REQUIRE(worst < 1e-3 * c.scale);
  }
}

TEST_CASE("unit-vector signals stay unit; the normal-similarity kernel keeps a crease", "[meanshift]") {
  // A closed box: its vertex normals are the face normals on the sides, mixed on the edges.
  const Mesh mesh = build(shapes::box(8, 8, 8));
  AttributeSet set(mesh.vertexCount());
  const std::vector<Vec3> normals = vertexNormals(mesh);
  std::vector<double> flat;
  for (const Vec3& n : normals) flat.insert(flat.end(), {n.x(), n.y(), n.z()});
  set.set("N", 3, AttributeKind::UnitVector, flat);
  for (RangeUpdate update : {RangeUpdate::Sampled, RangeUpdate::Joint}) {
    MeanShiftOptions o;
    o.channels = {{"N", 0.45, RangeKernel::NormalSimilarity}};
    o.spatialBandwidth = 1.5;
    o.radius = 3;
    o.rangeUpdate = update;
    const MeanShiftResult r = meanShift(mesh, set, o);
    const Attribute& out = r.signal.get("N");
    for (int v = 0; v < mesh.vertexCount(); ++v) {
      const Vec3 n(out.row(v)[0], out.row(v)[1], out.row(v)[2]);
      REQUIRE(n.norm() == Approx(1).margin(1e-12));
      // A vertex inside a side (not on an edge of the box) keeps its side's normal.
      const Vec3 p = mesh.position(v).cwiseAbs();
      if ((p.array() > 0.49).count() != 1) continue;
      const double fromEdge = 0.5 - (p.array() > 0.49).select(0.0, p.array()).maxCoeff();
      REQUIRE(n.dot(normals[v]) > 0.99);
      if (fromEdge > 0.2) REQUIRE(n.dot(normals[v]) > 0.999);
    }
  }
}

TEST_CASE("mean shift rejects bad input and can be cancelled", "[meanshift]") {
  const Mesh mesh = build(shapes::icosphere(2));
  const AttributeSet rgb = colors(std::vector<double>(3 * mesh.vertexCount(), 0.5));
  MeanShiftOptions o;
  o.spatialBandwidth = -1;
  REQUIRE_THROWS_AS(meanShift(mesh, rgb, o), InputError);
  o = {};
  o.channels = {{"MISSING", 0.1}};
  REQUIRE_THROWS_WITH(meanShift(mesh, rgb, o), Catch::Contains("MISSING"));
  o = {};
  o.channels = {{"COLOR", 0.1, RangeKernel::NormalSimilarity}};
  REQUIRE_THROWS_WITH(meanShift(mesh, rgb, o), Catch::Contains("unit-vector"));
  REQUIRE_THROWS_WITH(meanShift(mesh, colors({0, 0, 0}), MeanShiftOptions{}), Catch::Contains("vertices"));
  std::vector<double> bad(3 * mesh.vertexCount(), 0.5);
  bad[3 * 17 + 1] = std::nan("");
  REQUIRE_THROWS_WITH(meanShift(mesh, colors(bad), MeanShiftOptions{}), Catch::Contains("vertex 17"));

  std::atomic<bool> cancel{true};
  Progress progress;
  progress.cancel = &cancel;
  REQUIRE_THROWS_AS(meanShift(mesh, rgb, MeanShiftOptions{}, progress), Cancelled);
  // Raised during the run, from the progress callback: the call stops at the next chunk.
  cancel = false;
  int reports = 0;
  progress.report = [&](double, std::string_view) {
    if (++reports == 1) cancel = true;
  };
  MeanShiftOptions slow;
  slow.parallel.reportSeconds = 0;
  slow.parallel.chunk = 1;
  REQUIRE_THROWS_AS(meanShift(mesh, rgb, slow, progress), Cancelled);
  REQUIRE(reports == 1);
}

TEST_CASE("kept charts change no result, and spare log maps", "[meanshift]") {
  // A plane with a slot cut from its lower edge to y = 0.8: the cubes across it hold vertices on
  // both sides, which are near in space but far along the surface (around the slot's end), so
  // their climbs start in charts of their own, which blurring passes keep as they keep the cubes'.
  TriangleSoup soup = shapes::grid(40, 0.3);
  std::vector<Face> faces;
  for (const Face& f : soup.faces) {
    const Vec3 c = (soup.positions[f[0]] + soup.positions[f[1]] + soup.positions[f[2]]) / 3;
    if (!(std::abs(c.x() - 0.5) < 0.02 && c.y() < 0.8)) faces.push_back(f);
  }
  soup.faces = faces;
  const Mesh mesh = build(soup);
  const SurfaceGeometry geometry(mesh);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<double> rgb;
  for (int v = 0; v < mesh.vertexCount(); ++v)
    for (double c : {mesh.position(v).x() > 0.3 ? 0.9 : 0.1, 0.5, 0.2}) rgb.push_back(c + noise(rng));
  const AttributeSet noisy = colors(rgb);
  MeanShiftOptions o;
  o.spatialBandwidth = 2;
  o.rangeBandwidth = 0.3;
  o.tuning.chartDistortion = 0;  // cubes of h_s: more charts than a worker's own cache holds
  o.passes = 4;
  o.parallel.threads = 1;  // the counts of log maps depend on which worker climbs what
  const MeanShiftResult kept = meanShift(geometry, noisy, o);
  o.tuning.chartCacheBytes = 0;
  const MeanShiftResult none = meanShift(geometry, noisy, o);
  o.tuning.chartCacheBytes = 200000;  // some kept, the rest computed again
  const MeanShiftResult some = meanShift(geometry, noisy, o);
  for (const MeanShiftResult* r : {&none, &some}) {
    REQUIRE(r->signal.get("COLOR").values == kept.signal.get("COLOR").values);
    REQUIRE(r->iterations == kept.iterations);
  }
  // Every pass after the first reads every chart from what the first kept.
  CHECK(kept.diagnostics.chartsComputed < 2 * none.diagnostics.chartsComputed / o.passes);
  CHECK(kept.diagnostics.chartsComputed < some.diagnostics.chartsComputed);
  UNSCOPED_INFO("charts computed: kept " << kept.diagnostics.chartsComputed << ", some " << some.diagnostics.chartsComputed << ", none "
                                        << none.diagnostics.chartsComputed);
}

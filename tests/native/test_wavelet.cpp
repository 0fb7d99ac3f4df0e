// Graph-wavelet lifting: exact round trips, vanishing moments, the integral invariant, manifold coarse
// meshes without flips, the reduction per level, detail gains and bad input.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <vector>

#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/wavelet.hpp"
#include "support.hpp"

using namespace geoshift;

namespace {

Mesh meshOf(const TriangleSoup& s) { return buildMesh(s).mesh; }

// A color from the position (smooth) and the vertex normal as a unit-vector attribute.
AttributeSet signalsOf(const Mesh& m) {
  AttributeSet a(m.vertexCount());
  std::vector<double> color, normal;
  const std::vector<Vec3> n = vertexNormals(m);
  for (int v = 0; v < m.vertexCount(); ++v) {
    const Vec3& p = m.position(v);
    color.insert(color.end(), {0.5 + 0.5 * std::sin(3 * p.x()), 0.5 + 0.3 * p.y(), std::cos(p.z())});
    normal.insert(normal.end(), {n[v].x(), n[v].y(), n[v].z()});
  }
  a.set("color", 3, AttributeKind::Euclidean, color);
  a.set("normal", 3, AttributeKind::UnitVector, normal);
  return a;
}

double maxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

std::vector<double> flat(const std::vector<Vec3>& p) {
  std::vector<double> out;
  for (const Vec3& v : p) out.insert(out.end(), {v.x(), v.y(), v.z()});
  return out;
}

SynthesisResult resynthesize(const Multiresolution& mr, double alpha) {
  const std::vector<double> a = {alpha};
  return synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, a);
}

// V - E + F; a boundary edge has one half-edge, an interior one two.
int eulerCharacteristic(const Mesh& m) {
  int boundary = 0;
  for (int h = 0; h < m.halfedgeCount(); ++h) boundary += m.isBoundaryHalfedge(h);
  return m.vertexCount() - (m.halfedgeCount() + boundary) / 2 + m.faceCount();
}

}  // namespace

TEST_CASE("alpha = 1 reconstructs positions and attributes exactly, with the input connectivity") {
  struct Case {
    const char* name;
    TriangleSoup soup;
  };
  const std::vector<Case> cases = {{"sphere", shapes::icosphere(4)},
                                   {"torus", shapes::torus(64, 24)},
                                   {"grid with boundary", shapes::grid(60)},
                                   {"jittered grid", shapes::grid(60, 0.35, 7)}};
  for (const Case& c : cases) {
    SECTION(c.name) {
      const Mesh m = meshOf(c.soup);
      const AttributeSet signals = signalsOf(m);
      WaveletOptions o;
      o.levels = 4;
      const Multiresolution mr = analyze(m, signals, o);
      REQUIRE(mr.levelCount() == 4);
      const SynthesisResult r = resynthesize(mr, 1.0);
      const double diag = boundingBox(m.positions()).diagonal().norm();
      CHECK(maxDifference(flat(r.mesh.positions()), flat(m.positions())) <= 1e-6 * diag);
      CHECK(maxDifference(flat(r.mesh.positions()), flat(m.positions())) <= 1e-12 * diag);
      CHECK(r.mesh.faces() == m.faces());
      for (const std::string& name : {std::string("color"), std::string("normal")})
        CHECK(maxDifference(r.attributes.get(name).values, signals.get(name).values) < 1e-12);
      CHECK(r.attributes.get("normal").kind == AttributeKind::UnitVector);
    }
  }
}

TEST_CASE("levels = 0 is the identity and the coarse mesh is the input") {
  const Mesh m = meshOf(shapes::icosphere(2));
  WaveletOptions o;
  o.levels = 0;
  const Multiresolution mr = analyze(m, signalsOf(m), o);
  CHECK(mr.levelCount() == 0);
  CHECK(mr.coarse.vertexCount() == m.vertexCount());
  CHECK(mr.coarse.faces() == m.faces());
  CHECK(maxDifference(flat(resynthesize(mr, 0.0).mesh.positions()), flat(m.positions())) == 0);
}

TEST_CASE("a constant signal has zero details and stays constant on the coarse mesh") {
  const Mesh m = meshOf(shapes::grid(50, 0.3, 3));
  AttributeSet a(m.vertexCount());
  a.set("height", 1, AttributeKind::Euclidean, std::vector<double>(m.vertexCount(), 2.5));
  WaveletOptions o;
  o.levels = 5;
  const Multiresolution mr = analyze(m, a, o);
  REQUIRE(mr.levelCount() == 5);
  for (const WaveletLevel& L : mr.levels)
    for (size_t i = 0; i < L.odd.size(); ++i) REQUIRE(std::abs(L.detail[i * 4 + 3]) < 1e-12);
  for (double v : mr.coarseAttributes.get("height").values) CHECK(v == Approx(2.5).margin(1e-12));
}

TEST_CASE("a linear signal on a flat jittered grid has zero details with mean value weights") {
  // Jitter 0.3 keeps every input face counter-clockwise (0.35 already folds a few).
  const Mesh m = meshOf(shapes::grid(50, 0.3, 11));
  AttributeSet a(m.vertexCount());
  std::vector<double> f;
  for (const Vec3& p : m.positions()) f.push_back(2 * p.x() - 3 * p.y() + 1);
  a.set("linear", 1, AttributeKind::Euclidean, f);
  WaveletOptions o;
  o.levels = 4;
  const Multiresolution mr = analyze(m, a, o);
  int boundaryOdd = 0;
  for (const WaveletLevel& L : mr.levels)
    for (size_t i = 0; i < L.odd.size(); ++i) {
      // Positions are linear functions too: the whole detail row vanishes.
      for (int c = 0; c < 4; ++c) REQUIRE(std::abs(L.detail[i * 4 + c]) < 1e-12);
      boundaryOdd += L.offset[i + 1] - L.offset[i] == 2;
    }
  CHECK(boundaryOdd > 0);  // the check covered boundary vertices removed along the polyline

  o.weights = WaveletWeights::Uniform;  // not linear-reproducing on a jittered grid
  const Multiresolution uniform = analyze(m, a, o);
  double largest = 0;
  for (size_t i = 0; i < uniform.levels[0].odd.size(); ++i)
    largest = std::max(largest, std::abs(uniform.levels[0].detail[i * 4 + 3]));
  CHECK(largest > 1e-4);
}

TEST_CASE("the area-weighted sum of every signal is invariant across levels") {
  const Mesh m = meshOf(shapes::torus(48, 20));
  const AttributeSet signals = signalsOf(m);
  const std::vector<double> A0 = mixedVoronoiAreas(m);
  for (int levels = 1; levels <= 4; ++levels) {
    WaveletOptions o;
    o.levels = levels;
    const Multiresolution mr = analyze(m, signals, o);
    const std::vector<double>& color = signals.get("color").values;
    const std::vector<double>& coarseColor = mr.coarseAttributes.get("color").values;
    for (int c = 0; c < 3; ++c) {
      double fine = 0, coarse = 0, finePos = 0, coarsePos = 0;
      for (int v = 0; v < m.vertexCount(); ++v) fine += A0[v] * color[3 * v + c], finePos += A0[v] * m.position(v)[c];
      for (int v = 0; v < mr.coarse.vertexCount(); ++v)
        coarse += mr.coarseIntegrals[v] * coarseColor[3 * v + c],
            coarsePos += mr.coarseIntegrals[v] * mr.coarse.position(v)[c];
      CHECK(coarse == Approx(fine).epsilon(1e-12).margin(1e-12));
      CHECK(coarsePos == Approx(finePos).epsilon(1e-12).margin(1e-12));
    }
    double total = 0;
    for (double a : mr.coarseIntegrals) total += a;
    double fineTotal = 0;
    for (double a : A0) fineTotal += a;
    CHECK(total == Approx(fineTotal).epsilon(1e-12));
  }
}

TEST_CASE("alpha = 0 lowers the noise of a noisy sphere; the result is affine in alpha") {
  const Mesh clean = meshOf(shapes::icosphere(5));
  Mesh m = clean;
  NoiseOptions n;
  n.amount = 0.3;
  n.distribution = NoiseDistribution::Gaussian;
  n.direction = NoiseDirection::Normal;
  addNoise(m, n);
  auto rmsToClean = [&](const Mesh& r) {
    double s = 0;
    for (int v = 0; v < r.vertexCount(); ++v) s += (r.position(v) - clean.position(v)).squaredNorm();
    return std::sqrt(s / r.vertexCount());
  };
  const double noisy = rmsToClean(m);
  // Only the removed vertices lose their noise (the coarse ones keep theirs), so each level lowers it further.
  double previous = noisy;
  for (int levels = 1; levels <= 3; ++levels) {
    WaveletOptions o;
    o.levels = levels;
    const double smoothed = rmsToClean(resynthesize(analyze(m, {}, o), 0.0).mesh);
    CHECK(smoothed < 0.95 * previous);
    previous = smoothed;
  }
  CHECK(previous < 0.7 * noisy);

  WaveletOptions o;
  o.levels = 2;
  const Multiresolution mr = analyze(m, {}, o);
  const SynthesisResult smooth = resynthesize(mr, 0.0);
  CHECK(smooth.mesh.faces() == m.faces());

  // One gain for all levels enters linearly: f(2) - f(1) = f(1) - f(0), so 2 doubles every detail.
  const SynthesisResult one = resynthesize(mr, 1.0), two = resynthesize(mr, 2.0);
  double worst = 0;
  for (int v = 0; v < m.vertexCount(); ++v)
    worst = std::max(worst, ((two.mesh.position(v) - one.mesh.position(v)) -
                             (one.mesh.position(v) - smooth.mesh.position(v))).norm());
  CHECK(worst < 1e-12);
  CHECK(rmsToClean(two.mesh) > noisy);

  // A gain per level: suppressing only the finest details smooths less than suppressing both.
  const std::vector<double> perLevel = {0.0, 1.0};
  const SynthesisResult finest = synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, perLevel);
  CHECK(rmsToClean(finest.mesh) < noisy);
  CHECK(rmsToClean(finest.mesh) > rmsToClean(smooth.mesh));
}

TEST_CASE("every level is a manifold mesh with the input's topology and no flipped face") {
  Mesh noisy = meshOf(shapes::icosphere(4));
  addNoise(noisy, NoiseOptions{});
  const std::vector<std::pair<const char*, Mesh>> cases = {
      {"noisy sphere", noisy}, {"torus", meshOf(shapes::torus(60, 20))}, {"jittered grid", meshOf(shapes::grid(60, 0.4, 5))}};
  for (const auto& [name, m] : cases) {
    SECTION(name) {
      WaveletOptions o;
      o.levels = 5;
      o.keepLevelMeshes = true;
      const Multiresolution mr = analyze(m, {}, o);
      REQUIRE(mr.levelMeshes.size() == mr.levels.size() + 1);
      for (size_t k = 1; k < mr.levelMeshes.size(); ++k) {
        const WaveletLevelMesh& fine = mr.levelMeshes[k - 1];
        const WaveletLevelMesh& coarse = mr.levelMeshes[k];
        const Mesh& c = coarse.mesh;
        CHECK(eulerCharacteristic(c) == eulerCharacteristic(m));
        CHECK(c.boundaryLoops().size() == m.boundaryLoops().size());
        CHECK(c.vertexCount() == static_cast<int>(coarse.inputVertex.size()));
        CHECK(c.vertexCount() == mr.levels[k - 1].vertexCount - static_cast<int>(mr.levels[k - 1].odd.size()));
        int flipped = 0;
        for (int f = 0; f < c.faceCount(); ++f) {
          const Vec3 now = faceCross(c, f);
          const Vec3 before = faceCross(fine.mesh, coarse.parentFace[f]);
          flipped += !(now.dot(before) > 0);
        }
        CHECK(flipped == 0);
      }
    }
  }
}

TEST_CASE("each level removes 20-35% of the vertices of a large mesh, boundary included") {
  const std::vector<std::pair<const char*, TriangleSoup>> cases = {
      {"sphere", shapes::icosphere(6)}, {"grid", shapes::grid(200)}, {"jittered grid", shapes::grid(200, 0.3, 2)}};
  for (const auto& [name, soup] : cases) {
    SECTION(name) {
      const Mesh m = meshOf(soup);
      WaveletOptions o;
      o.levels = 6;
      const Multiresolution mr = analyze(m, {}, o);
      REQUIRE(mr.levelCount() == 6);
      const std::vector<int> counts = mr.vertexCounts();
      for (size_t k = 0; k + 1 < counts.size(); ++k) {
        const double removed = 1.0 - static_cast<double>(counts[k + 1]) / counts[k];
        INFO("level " << k << ": " << counts[k] << " -> " << counts[k + 1]);
        CHECK(removed >= 0.20);
        CHECK(removed <= 0.35);
      }
      if (!m.boundaryLoops().empty())
        CHECK(mr.coarse.boundaryLoops()[0].size() < 0.5 * m.boundaryLoops()[0].size());
    }
  }
}

TEST_CASE("bad input gives InputError naming the problem") {
  using test::errorOf;
  const Mesh m = meshOf(shapes::icosphere(2));
  WaveletOptions o;
  o.levels = -1;
  CHECK(errorOf([&] { analyze(m, {}, o); }).find("levels") != std::string::npos);
  o.levels = 3;
  const Multiresolution mr = analyze(m, signalsOf(m), o);
  const std::vector<double> two = {1.0, 0.5};
  CHECK(errorOf([&] { synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, two); }).find("alpha") !=
        std::string::npos);
  CHECK(errorOf([&] { waveletFilter(m, {}, o, two); }).find("alpha") != std::string::npos);
  const std::vector<double> nan = {std::nan("")};
  CHECK(errorOf([&] { synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, nan); }).find("finite") !=
        std::string::npos);
  const std::vector<double> one = {1.0};
  AttributeSet missing(mr.coarse.vertexCount());
  CHECK(errorOf([&] { synthesize(mr, mr.coarse.positions(), missing, one); }).find("color") != std::string::npos);
  std::vector<Vec3> fewer(mr.coarse.positions().begin(), mr.coarse.positions().end() - 1);
  CHECK(errorOf([&] { synthesize(mr, fewer, mr.coarseAttributes, one); }).find("positions") != std::string::npos);
  AttributeSet wrongCount(5);
  wrongCount.set("x", 1, AttributeKind::Euclidean, std::vector<double>(5, 0.0));
  CHECK(errorOf([&] { analyze(m, wrongCount, o); }).find("vertices") != std::string::npos);
}

TEST_CASE("cancelling through Progress stops the analysis") {
  const Mesh m = meshOf(shapes::icosphere(3));
  std::atomic<bool> cancel{true};
  Progress p;
  p.cancel = &cancel;
  CHECK_THROWS_AS(analyze(m, {}, WaveletOptions{}, p), Cancelled);
}

TEST_CASE("a piece given the whole's indices and cost bands removes the whole's vertices inside it") {
  // A tile of a larger mesh (docs/tiles.md#the-wavelet-order): the middle third of a jittered grid
  // with a margin of a sixth around it, analysed in the whole's order, keeps exactly the coarse
  // vertices the whole keeps in the middle third.
  const Mesh whole = meshOf(shapes::grid(150, 0.3, 4));
  WaveletOptions o;
  o.levels = 3;
  const Multiresolution all = analyze(whole, {}, o);
  Vec3 lo = whole.position(0), hi = lo;
  for (int v = 0; v < whole.vertexCount(); ++v) {
    lo = lo.cwiseMin(whole.position(v));
    hi = hi.cwiseMax(whole.position(v));
  }
  const Vec3 side = hi - lo;
  const auto inside = [&](int v, double from, double to) {
    const Vec3 f = (whole.position(v) - lo).cwiseQuotient(side);
    return f.x() >= from && f.x() <= to && f.y() >= from && f.y() <= to;
  };
  std::vector<int> local(whole.vertexCount(), -1);
  std::vector<Vec3> positions;
  for (int v = 0; v < whole.vertexCount(); ++v)
    if (inside(v, 1.0 / 6, 5.0 / 6)) {
      local[v] = static_cast<int>(o.wholeIndex.size());
      o.wholeIndex.push_back(v);
      positions.push_back(whole.position(v));
    }
  std::vector<Face> faces;
  for (int f = 0; f < whole.faceCount(); ++f) {
    const Face& t = whole.face(f);
    if (local[t[0]] >= 0 && local[t[1]] >= 0 && local[t[2]] >= 0) faces.push_back({local[t[0]], local[t[1]], local[t[2]]});
  }
  const Mesh piece(positions, faces);
  for (const WaveletLevel& l : all.levels) o.costBounds.push_back(l.costBounds);
  const Multiresolution part = analyze(piece, {}, o);

  std::vector<char> keptWhole(whole.vertexCount(), 0), keptPiece(whole.vertexCount(), 0);
  for (int v : all.coarseToFine) keptWhole[v] = 1;
  for (int v : part.coarseToFine) keptPiece[o.wholeIndex[v]] = 1;
  int core = 0, same = 0;
  for (int v = 0; v < whole.vertexCount(); ++v)
    if (inside(v, 1.0 / 3, 2.0 / 3)) {
      ++core;
      same += keptWhole[v] == keptPiece[v];
    }
  CHECK(core > 2000);
  CHECK(same == core);

  // Malformed orders are refused, naming what is wrong.
  WaveletOptions bad = o;
  bad.wholeIndex.pop_back();
  CHECK(test::errorOf([&] { analyze(piece, {}, bad); }).find("wholeIndex") != std::string::npos);
  bad = o;
  std::swap(bad.wholeIndex[0], bad.wholeIndex[1]);
  CHECK(test::errorOf([&] { analyze(piece, {}, bad); }).find("increasing") != std::string::npos);
  bad = o;
  bad.costBounds[1] = {2.0, 1.0};
  CHECK(test::errorOf([&] { analyze(piece, {}, bad); }).find("ascending") != std::string::npos);
}

// The default denoiser's risk estimate (core/src/denoise_risk.hpp, docs/denoising.md#the-risk-estimate),
// white-box: the spaced probe's divergence against the exact trace of a linear smoother computed
// vertex by vertex, and the bound that keeps a jump in one probed vertex from swinging the risk.
#include <catch2/catch.hpp>

#include <cmath>

#include "denoise_detail.hpp"
#include "denoise_risk.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/smoothing.hpp"
#include "denoise_support.hpp"

using namespace geoshift;
using namespace geoshift::denoise_detail;
using namespace geoshift::test;

namespace {

std::vector<Vec3> taubin(Mesh& work, const std::vector<Vec3>& start, int steps) {
  work.positions() = start;
  TaubinOptions o;
  o.iterations = steps;
  taubinSmooth(work, o);
  return work.positions();
}

// Column v of the Jacobian J of `steps` Taubin steps along N: each vertex's response to input vertex
// v moved by sigma along its N, over sigma (Taubin is linear, so any step will do).
std::vector<double> jacobianColumn(Mesh& work, const std::vector<Vec3>& input, const std::vector<Vec3>& x,
                                   const std::vector<Vec3>& n, double sigma, int steps, int v) {
  std::vector<Vec3> moved = input;
  moved[v] += sigma * n[v];
  const std::vector<Vec3> out = taubin(work, moved, steps);
  std::vector<double> column(out.size());
  for (size_t u = 0; u < out.size(); ++u) column[u] = (out[u] - x[u]).dot(n[u]) / sigma;
  return column;
}

// An icosphere with Gaussian noise of 0.3 AEL along its normals, and a mesh to compute on.
struct NoisySphere {
  explicit NoisySphere(std::uint64_t seed)
      : noisy(withNoise(buildMesh(shapes::icosphere(3)).mesh, 0.3, seed)), input(noisy.positions()),
        sigma(0.3 * averageEdgeLength(noisy)), work(noisy) {}
  Mesh noisy;
  std::vector<Vec3> input;
  double sigma;
  Mesh work;
};

}  // namespace

TEST_CASE("risk estimate: the probe's divergence of Taubin smoothing matches its exact trace", "[denoise][risk]") {
  NoisySphere s(5);
  auto& [noisy, input, sigma, work] = s;
  for (bool bounded : {false, true}) {
    RiskOptions o;
    o.probeSpacing = 1;  // every vertex: the estimate is then tr J up to the probe's cross terms
    o.boundedDivergence = bounded;
    const RiskEstimate risk(work, input, sigma, 1, o);
    const std::vector<Vec3>& n = risk.normals();
    const std::vector<Vec3> x = taubin(work, input, 3);
    const RiskSums sums = risk.sums(x, taubin(work, risk.probedInput(), 3));
    // Exact trace: the diagonal of J, one column at a time.
    double trace = 0;
    for (int v = 0; v < noisy.vertexCount(); ++v) trace += jacobianColumn(work, input, x, n, sigma, 3, v)[v];
    INFO("bounded " << bounded << ": probe " << sums.div << ", exact trace " << trace << " over "
                    << noisy.vertexCount() << " vertices");
    // Each vertex's own derivative lies in (0, 1): Taubin is a smoother.
    REQUIRE(trace > 0);
    REQUIRE(trace < noisy.vertexCount());
    // The probe's cross terms (±J_ij, i ≠ j) are its only error: a few per cent of the trace.
    REQUIRE(sums.div == Approx(trace).epsilon(0.1));
  }
}

TEST_CASE("risk estimate: a jump at one probed vertex moves the bounded divergence by at most that vertex's share",
          "[denoise][risk]") {
  NoisySphere s(7);
  auto& [noisy, input, sigma, work] = s;
  RiskOptions bounded, raw;
  raw.boundedDivergence = false;
  const RiskEstimate withBound(work, input, sigma, 1, bounded);
  const RiskEstimate without(work, input, sigma, 1, raw);
  REQUIRE(withBound.probedVertices() > 1);
  REQUIRE(withBound.probedVertices() < noisy.vertexCount() / 4);  // spaced 5 edges apart

  const std::vector<Vec3> x = taubin(work, input, 3);
  std::vector<Vec3> xp = taubin(work, withBound.probedInput(), 3);
  const RiskSums smooth = withBound.sums(x, xp);
  REQUIRE(without.sums(x, xp).div == Approx(smooth.div).epsilon(1e-12));  // no term outside [0, 1]

  // The probed copy of one probed vertex lands half an edge away, as when the flip guard decides
  // differently for the input and the probe: a difference quotient of about 50 / 0.003 alone.
  const std::vector<Vec3>& n = withBound.normals();
  const std::vector<Vec3> probed = withBound.probedInput();
  int v = 0;
  while ((probed[v] - input[v]).squaredNorm() == 0) ++v;
  xp[v] -= 0.5 * averageEdgeLength(noisy) * n[v] * ((probed[v] - input[v]).dot(n[v]) > 0 ? 1 : -1);
  const double share = static_cast<double>(noisy.vertexCount()) / withBound.probedVertices();
  const RiskSums jumped = withBound.sums(x, xp), rawJumped = without.sums(x, xp);
  INFO("divergence " << smooth.div << "; with the jump, bounded " << jumped.div << ", raw " << rawJumped.div);
  REQUIRE(std::abs(jumped.div - smooth.div) <= share * 1.0 + 1e-9);
  REQUIRE(rawJumped.div < smooth.div - 100 * share);  // the raw quotient swings by far more
  REQUIRE(jumped.fit == rawJumped.fit);
}

TEST_CASE("risk estimate: another seed draws other signs on the same vertices, and a seed's signs come back",
          "[denoise][risk]") {
  NoisySphere s(3);
  auto& [noisy, input, sigma, work] = s;
  RiskOptions first, second;
  second.seed = 99;
  RiskEstimate risk(work, input, sigma, 1, first);
  const RiskEstimate other(work, input, sigma, 1, second);
  const std::vector<Vec3> p1 = risk.probedInput(), p2 = other.probedInput();
  risk.reseed(99);
  REQUIRE(risk.probedInput() == p2);  // reseeding draws as the constructor does
  int moved = 0, flipped = 0;
  for (int v = 0; v < noisy.vertexCount(); ++v) {
    const double a = (p1[v] - input[v]).dot(risk.normals()[v]), b = (p2[v] - input[v]).dot(risk.normals()[v]);
    REQUIRE((a == 0) == (b == 0));  // the same vertices are probed
    if (a != 0) ++moved;
    if (a * b < 0) ++flipped;
  }
  INFO(flipped << " of " << moved << " probed vertices changed sign");
  REQUIRE(moved == risk.probedVertices());
  REQUIRE(flipped > 0);
  REQUIRE(flipped < moved);
  risk.reseed(first.seed);
  REQUIRE(risk.probedInput() == p1);
}

TEST_CASE("risk estimate: the probe's gain of Taubin smoothing matches its exact tr JᵀJ", "[denoise][risk]") {
  NoisySphere s(11);
  auto& [noisy, input, sigma, work] = s;
  const RiskEstimate risk(work, input, sigma, 1, RiskOptions{});
  const std::vector<Vec3>& n = risk.normals();
  const std::vector<Vec3> x = taubin(work, input, 8);
  const RiskSums sums = risk.sums(x, taubin(work, risk.probedInput(), 8));
  // Exact: the squared length of every column of J.
  double exact = 0;
  for (int v = 0; v < noisy.vertexCount(); ++v)
    for (double r : jacobianColumn(work, input, x, n, sigma, 8, v)) exact += r * r;
  INFO("probe " << sums.gain << ", exact " << exact << ", divergence " << sums.div << " over " << noisy.vertexCount()
                << " vertices");
  REQUIRE(exact > 0);
  REQUIRE(exact < sums.div);  // a smoother's JᵀJ has a smaller trace than J
  REQUIRE(sums.gain == Approx(exact).epsilon(0.15));
}

TEST_CASE("risk estimate: a linear candidate implies the noise's variance, the general bound lies above it",
          "[denoise][risk][noise]") {
  // On a sphere smoothing takes next to nothing from the shape, so Σ e² is the noise it removes:
  // σ² (m − 2 tr J + tr JᵀJ) in expectation (docs/denoising.md#the-noise-level).
  for (std::uint64_t seed : {2, 13}) {
    NoisySphere s(seed);
    auto& [noisy, input, sigma, work] = s;
    const RiskEstimate risk(work, input, sigma, 1, RiskOptions{});
    // The noise's realized variance along N, which the estimates aim at.
    const Mesh clean = buildMesh(shapes::icosphere(3)).mesh;
    double variance = 0;
    for (int v = 0; v < noisy.vertexCount(); ++v)
      variance += std::pow((input[v] - clean.position(v)).dot(risk.normals()[v]), 2) / noisy.vertexCount();
    for (int steps : {8, 15}) {
      const std::vector<Vec3> x = taubin(work, input, steps);
      const RiskSums sums = risk.sums(x, taubin(work, risk.probedInput(), steps));
      const double linear = risk.linearImpliedVariance(sums), general = risk.impliedVariance(sums);
      INFO("seed " << seed << ", " << steps << " steps: realized " << variance << ", linear " << linear << ", general "
                   << general);
      REQUIRE(linear == Approx(variance).epsilon(0.12));
      REQUIRE(general > 1.1 * linear);
    }
  }
}

TEST_CASE("risk estimate: the probe's edge divergence of Taubin smoothing matches its exact tr(L J)", "[denoise][risk]") {
  NoisySphere s(17);
  auto& [noisy, input, sigma, work] = s;
  RiskOptions o;
  o.gradientWeight = 1;
  const RiskEstimate risk(work, input, sigma, 1, o);
  const std::vector<Vec3>& n = risk.normals();
  const std::vector<Vec3> probed = risk.probedInput();
  const std::vector<Vec3> x = taubin(work, input, 3);
  const RiskSums sums = risk.sums(x, taubin(work, probed, 3));
  // Exact, over the probed vertices and scaled up as the estimate is: (L J)_vv = degree_v J_vv − Σ_{u~v} J_uv,
  // L the graph Laplacian, from column v of J.
  // The scale is L's trace (twice the edges) over the part of it the probed vertices cover.
  double exact = 0, probedDegree = 0;
  int probedCount = 0;
  for (int v = 0; v < noisy.vertexCount(); ++v) {
    if (probed[v] == input[v]) continue;
    ++probedCount;
    const std::vector<double> column = jacobianColumn(work, input, x, n, sigma, 3, v);
    const std::vector<int> around = noisy.neighbors(v);
    probedDegree += around.size();
    exact += around.size() * column[v];
    for (int u : around) exact -= column[u];
  }
  REQUIRE(probedCount == risk.probedVertices());
  exact *= 2.0 * (noisy.halfedgeCount() / 2) / probedDegree;
  INFO("probe " << sums.edgeDiv << ", exact " << exact << " over " << probedCount << " probed vertices");
  // Smoothing makes a vertex follow its neighbours: L J's diagonal is positive and below L's (the degree).
  REQUIRE(exact > 0);
  REQUIRE(exact < 6 * noisy.vertexCount());
  // Only the cross terms of probed vertices five edges apart separate the two.
  REQUIRE(sums.edgeDiv == Approx(exact).epsilon(0.05));
}

TEST_CASE("risk estimate: the edge-difference risk is unbiased for the error's differences across edges",
          "[denoise][risk]") {
  // Along N, E Σ_edges (err_i − err_j)² = Σ (e_i − e_j)² − σ² tr L + 2σ² tr(L J); on a sphere, with σ
  // the noise's realized spread along N, the estimate lands on the realized value for every
  // candidate: the identity (about σ² per edge over 2, the noise's own), light and heavy smoothing.
  // The position's risk of the same candidates lands as near (0.002–0.026 σ² low).
  const Mesh clean = buildMesh(shapes::icosphere(3)).mesh;
  for (std::uint64_t seed : {3, 19}) {
    NoisySphere s(seed);
    auto& [noisy, input, sigma, work] = s;
    RiskOptions o;
    o.gradientWeight = 1;
    const RiskEstimate risk(work, input, sigma, 1, o);
    const std::vector<Vec3>& n = risk.normals();
    double variance = 0;
    for (int v = 0; v < noisy.vertexCount(); ++v)
      variance += std::pow((input[v] - clean.position(v)).dot(n[v]), 2) / noisy.vertexCount();
    sigma = std::sqrt(variance);  // the fixed-magnitude noise in random directions: about a third of its square
    for (int steps : {0, 3, 15}) {
      const std::vector<Vec3> x = taubin(work, input, steps);
      const Risk r = risk.at(risk.sums(x, taubin(work, risk.probedInput(), steps)), sigma);
      double realized = 0;
      int edges = 0;
      for (int h = 0; h < noisy.halfedgeCount(); ++h) {
        const int a = noisy.tail(h), b = noisy.head(h);
        if (a > b) continue;
        realized += std::pow((x[a] - clean.position(a)).dot(n[a]) - (x[b] - clean.position(b)).dot(n[b]), 2);
        ++edges;
      }
      realized /= 2 * edges;
      INFO("seed " << seed << ", " << steps << " steps: estimate " << r.gradient / (sigma * sigma) << " σ², realized "
                   << realized / (sigma * sigma) << " σ²");
      // Within 0.03 σ²: N comes from the noisy input, which biases this estimate low a little, as it
      // does the position's (docs/denoising.md#the-risk-estimate); a wrong constant would be off by σ².
      REQUIRE(std::abs(r.gradient - realized) < 0.03 * sigma * sigma);
      REQUIRE(r.ranked == Approx(r.position + r.gradient));
    }
  }
}

// docs/denoising.md#the-blend-of-least-risk. The blend (1 − w) x_W + w x_O has the risk
// (1 − w) R_W + w R_O − w (1 − w) D; the weight taken must be where that is least over [0, 1],
// checked against a dense grid of weights.
TEST_CASE("the blend's weight is the one of least risk", "[denoise][blend]") {
  auto risk = [](double w, double gap, double d) { return w * gap - w * (1 - w) * d; };  // R_W = 0
  for (double d : {0.002, 0.01, 0.03, 0.1, 0.19}) {
    for (double gap = -0.25; gap <= 0.25; gap += 0.0125) {
      const double w = blendWeight(gap, d, 1);
      INFO("gap " << gap << ", D " << d << ": weight " << w);
      REQUIRE(w >= 0);
      REQUIRE(w <= 1);
      double bestRisk = risk(0, gap, d), bestW = 0;
      for (int i = 1; i <= 100000; ++i) {
        const double t = i / 100000.0;
        if (risk(t, gap, d) < bestRisk) bestRisk = risk(t, gap, d), bestW = t;
      }
      REQUIRE(risk(w, gap, d) <= bestRisk + 1e-12);
      REQUIRE(std::abs(w - bestW) <= 1e-4);
      // The spread scales D.
      REQUIRE(blendWeight(gap, d, 2.5) == Approx(blendWeight(gap, 2.5 * d, 1)).margin(1e-15));
    }
  }
  REQUIRE(blendWeight(0.0, 0.05, 1) == 0.5);  // equal ranks: half and half
  REQUIRE(blendWeight(0.05, 0.05, 1) == 0.0);  // behind by D: nothing
  REQUIRE(blendWeight(-0.1, 0.05, 1) == 1.0);  // ahead by D or more: the other alone
  REQUIRE(blendWeight(-0.1, 0.0, 1) == 0.0);  // no difference: no weight
  REQUIRE(blendWeight(0.0, 0.05, 0) == 0.0);
}

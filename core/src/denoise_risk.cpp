// RiskEstimate (denoise_risk.hpp; docs/denoising.md#the-risk-estimate).
//
// With y the input, x = D(y) a candidate, N fixed directions, e = (x − y)·N per vertex and the noise
// along N of variance σ² per vertex, Stein's lemma gives
//   E[|(x − x*)·N|²] = E[|e|²] − mσ² + 2σ² E[tr J],  J = ∂(x·N)/∂(y·N),
// and tr J ≈ bᵀ (x' − x)·N / ε for a ±1 probe b, x' = D(y + ε b N). With boundedDivergence each
// probed vertex's term b_i (x'_i − x_i)·N_i / ε is kept within [0, 1], the range of a smoother's own
// derivative J_ii: a larger one is a jump, not a derivative (docs/denoising.md#the-risk-estimate).
// The gain ‖(x' − x)·N / ε‖² estimates tr JᵀJ the same way, each vertex's term kept at most 1; for a
// linear candidate it tightens the bound on σ² (docs/denoising.md#the-noise-level).
// The error's differences across edges follow the same way with L the graph Laplacian (GᵀG for G the
// edge differences): E‖G(x − x*)‖² = ‖G e‖² − σ² tr L + 2σ² tr(L J), tr(L J) from the probe as
// bᵀ L (x' − x)·N / ε, each probed vertex's term kept within [0, its degree].
#include "denoise_risk.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift::denoise_detail {

namespace {

// Greedy choice of vertices at least `spacing` edges apart, in the order of `order` (the i-th vertex
// visited is order[i]; null: index order).
std::vector<char> spacedVertices(const Mesh& mesh, const std::vector<Vec3>& normals, int spacing,
                                 const std::vector<int>* order) {
  const int n = mesh.vertexCount();
  std::vector<char> chosen(n, 0);
  if (spacing <= 1) {
    for (int v = 0; v < n; ++v) chosen[v] = normals[v].squaredNorm() > 0;
    return chosen;
  }
  std::vector<int> blockedBy(n, -1), depth(n, 0), queue;
  for (int i = 0; i < n; ++i) {
    const int v = order ? (*order)[i] : i;
    if (blockedBy[v] >= 0 || normals[v].squaredNorm() == 0) continue;
    chosen[v] = 1;
    // Block the ball of radius spacing − 1 around v (breadth first over edges).
    queue.assign(1, v);
    blockedBy[v] = v;
    depth[v] = 0;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int a = queue[q];
      if (depth[a] + 1 >= spacing) continue;
      mesh.forEachOutgoing(a, [&](int h) {
        for (int b : {mesh.head(h), mesh.tail(Mesh::prev(h))}) {
          if (blockedBy[b] == v) continue;
          if (blockedBy[b] < 0 || depth[b] > depth[a] + 1) {
            blockedBy[b] = v;
            depth[b] = depth[a] + 1;
            queue.push_back(b);
          }
        }
      });
    }
  }
  return chosen;
}

}  // namespace

RiskEstimate::RiskEstimate(Mesh& work, const std::vector<Vec3>& input, double sigma, double strength,
                           const RiskOptions& options)
    : mesh_(work), input_(input), sigma_(sigma), strength_(strength), eps_(0.01 * sigma * strength),
      boundedDivergence_(options.boundedDivergence), gradientWeight_(options.gradientWeight),
      visitOrder_(options.visitOrder) {
  const int n = work.vertexCount();
  if (visitOrder_ && static_cast<int>(visitOrder_->size()) != n)
    throw InputError("risk estimate: a visit order of " + std::to_string(visitOrder_->size()) + " vertices for " +
                     std::to_string(n));
  work.positions() = input;
  if (options.normalSmoothing > 0) {
    TaubinOptions taubin = options.taubin;
    taubin.iterations = options.normalSmoothing;
    taubinSmooth(work, taubin);
  }
  normals_ = vertexNormals(work);
  for (int h = 0; h < work.halfedgeCount(); ++h)
    if (countsEdge(h)) ++edges_;
  const std::vector<char> chosen = spacedVertices(work, normals_, options.probeSpacing, visitOrder_);
  probe_.assign(n, 0);
  std::mt19937_64 rng(options.seed);
  for (int i = 0; i < n; ++i) {
    const int v = visitOrder_ ? (*visitOrder_)[i] : i;
    // One draw per vertex whatever the spacing, so a vertex's sign does not depend on the others.
    const signed char sign = (rng() >> 63) ? 1 : -1;
    if (normals_[v].squaredNorm() > 0) ++measured_;
    if (chosen[v]) {
      probe_[v] = sign;
      ++probed_;
      for (int u : work.neighbors(v)) probedDegree_ += normals_[u].squaredNorm() > 0;
    }
  }
}

void RiskEstimate::reseed(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (size_t i = 0; i < probe_.size(); ++i) {
    signed char& b = probe_[visitOrder_ ? (*visitOrder_)[i] : i];
    const signed char sign = (rng() >> 63) ? 1 : -1;  // one draw per vertex, as in the constructor
    if (b != 0) b = sign;
  }
}

std::vector<Vec3> RiskEstimate::probedInput() const {
  std::vector<Vec3> out = input_;
  for (size_t v = 0; v < out.size(); ++v)
    if (probe_[v] != 0) out[v] += eps_ * probe_[v] * normals_[v];
  return out;
}

bool RiskEstimate::countsEdge(int h) const {
  const int a = mesh_.tail(h), b = mesh_.head(h);
  return (mesh_.twin(h) < 0 || a < b) && normals_[a].squaredNorm() > 0 && normals_[b].squaredNorm() > 0;
}

RiskSums RiskEstimate::sums(const std::vector<Vec3>& x, const std::vector<Vec3>& xp) const {
  double fit = 0, div = 0, gain = 0, edgeFit = 0, edgeDiv = 0;
  auto error = [&](int v) { return (x[v] - input_[v]).dot(normals_[v]); };
  auto response = [&](int v) { return (xp[v] - x[v]).dot(normals_[v]) / eps_; };
  for (size_t v = 0; v < x.size(); ++v) {
    const double e = error(v);
    fit += e * e;
    const double r = response(v);
    gain += std::min(r * r, 1.0);  // a jump counts as a full response, as in div
    if (probe_[v] == 0) continue;
    const double term = probe_[v] * r;
    div += boundedDivergence_ ? std::clamp(term, 0.0, 1.0) : term;
    // The edge differences' part, b_v (L (x' − x)·N / ε)_v: its own response once per measured edge,
    // less its neighbours'; within [0, degree] as its own term is within [0, 1].
    if (gradientWeight_ == 0) continue;
    int degree = 0;
    double neighbours = 0;
    for (int u : mesh_.neighbors(static_cast<int>(v)))
      if (normals_[u].squaredNorm() > 0) {
        ++degree;
        neighbours += response(u);
      }
    const double edgeTerm = probe_[v] * (degree * r - neighbours);
    edgeDiv += boundedDivergence_ ? std::clamp(edgeTerm, 0.0, static_cast<double>(degree)) : edgeTerm;
  }
  if (gradientWeight_ != 0)
    for (int h = 0; h < mesh_.halfedgeCount(); ++h)
      if (countsEdge(h)) {
        const double d = error(mesh_.tail(h)) - error(mesh_.head(h));
        edgeFit += d * d;
      }
  // The probe covers probed_ of the measured_ vertices: the traces are scaled up to all of them, the
  // edge part by L's diagonal (the degrees) it covers.
  const double scale = probed_ > 0 ? static_cast<double>(measured_) / probed_ : 0.0;
  const double edgeScale = probedDegree_ > 0 ? 2 * edges_ / probedDegree_ : 0.0;
  return {fit, div * scale, gain * scale, edgeFit, edgeDiv * edgeScale};
}

Risk RiskEstimate::at(const RiskSums& r, double sigma) const {
  const double m = std::max(1, measured_);
  auto position = [&](double s) { return (r.fit - m * s * s + 2 * s * s * r.div) / m; };
  // E Σ_edges ((x − x*)_i − (x − x*)_j)² along N = Σ (e_i − e_j)² − σ² tr L + 2σ² tr(L J), L the
  // graph Laplacian of the edges (tr L = 2 × edges); over 2 × edges, so that the input reads σ².
  const double twoE = std::max(1.0, 2.0 * edges_);
  auto gradient = [&](double s) { return (r.edgeFit - twoE * s * s + 2 * s * s * r.edgeDiv) / twoE; };
  Risk out{position(sigma * strength_), position(sigma), gradient(sigma * strength_), 0};
  out.ranked = out.position + gradientWeight_ * out.gradient;
  return out;
}

namespace {
double boundOver(double fit, double denominator, double m) { return denominator > 0.5 * m ? fit / denominator : 0.0; }
}  // namespace

double RiskEstimate::impliedVariance(const RiskSums& r) const {
  const double m = std::max(1, measured_);
  return boundOver(r.fit, m - 2 * r.div, m);
}

double RiskEstimate::linearImpliedVariance(const RiskSums& r) const {
  const double m = std::max(1, measured_);
  return boundOver(r.fit, m - 2 * r.div + r.gain, m);
}

}  // namespace geoshift::denoise_detail

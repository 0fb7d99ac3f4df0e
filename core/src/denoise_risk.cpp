// RiskEstimate (denoise_risk.hpp; docs/denoising.md#the-risk-estimate).
//
// With y the input, x = D(y) a candidate, N fixed directions, e = (x − y)·N per vertex and the noise
// along N of variance σ² per vertex, Stein's lemma gives for any symmetric positive semidefinite L
//   E[(x − x*)ᵀ L (x − x*)] = E[eᵀ L e] − σ² tr L + 2σ² E[tr(L J)],  J = ∂(x·N)/∂(y·N),
// and tr(L J) ≈ bᵀ L (x' − x)·N / ε for a ±1 probe b, x' = D(y + ε b N). L = I is the classic SURE
// of positions; L = the cotangent Laplacian (Σ_f A_f |∇_f e|² = eᵀ L e) gives the normal risk.
#include "denoise_risk.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "geoshift/geometry.hpp"

namespace geoshift::denoise_detail {

namespace {

// Greedy choice of vertices at least `spacing` edges apart, in index order.
std::vector<char> spacedVertices(const Mesh& mesh, const std::vector<Vec3>& normals, int spacing) {
  const int n = mesh.vertexCount();
  std::vector<char> chosen(n, 0);
  if (spacing <= 1) {
    for (int v = 0; v < n; ++v) chosen[v] = normals[v].squaredNorm() > 0;
    return chosen;
  }
  std::vector<int> blockedBy(n, -1), depth(n, 0), queue;
  for (int v = 0; v < n; ++v) {
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
    : mesh_(work), input_(input), sigma_(sigma), sigmaRanked_(sigma * strength), eps_(0.01 * sigma * strength) {
  const int n = work.vertexCount(), nf = work.faceCount();
  work.positions() = input;
  if (options.normalSmoothing > 0) {
    TaubinOptions taubin = options.taubin;
    taubin.iterations = options.normalSmoothing;
    taubinSmooth(work, taubin);
  }
  normals_ = vertexNormals(work);
  // Half the cotangent of each corner's angle on the smoothed copy: the weight of the opposite edge
  // in A |∇e|² over that face (non-negative over a face whatever its angles).
  cot_.assign(3 * static_cast<size_t>(nf), 0.0f);
  for (int f = 0; f < nf; ++f) {
    const Face& t = work.face(f);
    const double twiceArea = faceCross(work, f).norm();
    if (!(twiceArea > 0)) continue;
    area_ += twiceArea / 2;
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = work.position(t[(k + 1) % 3]) - work.position(t[k]);
      const Vec3 w = work.position(t[(k + 2) % 3]) - work.position(t[k]);
      const double c = 0.5 * u.dot(w) / twiceArea;
      cot_[3 * f + k] = static_cast<float>(c);
      // The edge opposite corner k joins the other two corners: its weight is on both diagonals.
      for (int j : {t[(k + 1) % 3], t[(k + 2) % 3]})
        if (normals_[j].squaredNorm() > 0) traceL_ += c;
    }
  }
  const std::vector<char> chosen = spacedVertices(work, normals_, options.probeSpacing);
  probe_.assign(n, 0);
  std::mt19937_64 rng(options.seed);
  for (int v = 0; v < n; ++v) {
    // One draw per vertex whatever the spacing, so a vertex's sign does not depend on the others.
    const signed char sign = (rng() >> 63) ? 1 : -1;
    if (normals_[v].squaredNorm() > 0) ++measured_;
    if (chosen[v]) {
      probe_[v] = sign;
      ++probed_;
    }
  }
}

std::vector<Vec3> RiskEstimate::probedInput() const {
  std::vector<Vec3> out = input_;
  for (size_t v = 0; v < out.size(); ++v)
    if (probe_[v] != 0) out[v] += eps_ * probe_[v] * normals_[v];
  return out;
}

Risk RiskEstimate::operator()(const std::vector<Vec3>& x, const std::vector<Vec3>& xp) const {
  const int n = static_cast<int>(x.size());
  // e: the candidate's displacement along N; delta: the probe's response along N.
  std::vector<double> e(n), delta(n);
  double fit = 0, div = 0;
  for (int v = 0; v < n; ++v) {
    e[v] = (x[v] - input_[v]).dot(normals_[v]);
    delta[v] = (xp[v] - x[v]).dot(normals_[v]);
    fit += e[v] * e[v];
    div += probe_[v] * delta[v];
  }
  double fitL = 0, divL = 0;
  for (int f = 0; f < mesh_.faceCount(); ++f) {
    const Face& t = mesh_.face(f);
    for (int k = 0; k < 3; ++k) {
      const double w = cot_[3 * f + k];
      if (w == 0) continue;
      const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
      const double de = e[a] - e[b];
      fitL += w * de * de;
      divL += w * (probe_[a] - probe_[b]) * (delta[a] - delta[b]);
    }
  }
  // The probe covers probed_ of the measured_ vertices: the traces are scaled up to all of them.
  const double scale = probed_ > 0 ? static_cast<double>(measured_) / probed_ : 0.0;
  div = div * scale / eps_;
  divL = divL * scale / eps_;
  const double m = std::max(1, measured_), area = area_ > 0 ? area_ : 1.0;
  auto position = [&](double s) { return (fit - m * s * s + 2 * s * s * div) / m; };
  auto normal = [&](double s) { return (fitL - traceL_ * s * s + 2 * s * s * divL) / area; };
  return {position(sigmaRanked_), normal(sigmaRanked_), position(sigma_), normal(sigma_)};
}

}  // namespace geoshift::denoise_detail

#pragma once
// The default denoiser's risk estimate (docs/denoising.md#the-risk-estimate): Stein's unbiased
// risk estimate of a candidate's error, from the candidate and the same candidate computed from a
// probed copy of the input (Monte-Carlo SURE, Ramani, Blu and Unser 2008). Two losses, both
// measured along the normals N of a lightly smoothed copy of the input:
//  - position: the mean squared displacement error e_i = (x_i − x*_i)·N_i over the vertices;
//  - normal: the Dirichlet energy Σ_f A_f |∇_f e|² of that error over the surface, divided by its
//    area: to first order, the mean squared angle between the candidate's face normals and the
//    truth's (a vertex moved by e along the normal tilts each of its faces by e / height).
#include <cstdint>
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/smoothing.hpp"

namespace geoshift::denoise_detail {

struct RiskOptions {
  int normalSmoothing = 6;  // Taubin steps of the copy that gives N and the Dirichlet weights
  TaubinOptions taubin;     // its λ, μ and weights (the iteration count is normalSmoothing)
  std::uint64_t seed = 1;   // of the probe's signs
  // 1: every vertex is probed (±1 each). d > 1: only vertices at least d edges apart from each other
  // (chosen greedily in index order), so that the probe's cross terms, which carry its randomness,
  // mostly vanish; the divergence is scaled up from the probed vertices to all.
  int probeSpacing = 1;
};

// Both risks of a candidate: position in squared length per vertex, normal in rad² (area mean):
// `ranked` with σ times the strength (what candidates are ranked by), `unbiased` with σ.
struct Risk {
  double position = 0, normal = 0;
  double positionUnbiased = 0, normalUnbiased = 0;
};

class RiskEstimate {
 public:
  // `work` supplies the connectivity; its positions are overwritten (the caller restores them).
  // sigma: the noise level in the mesh's units, strength: its multiplier for ranking.
  RiskEstimate(Mesh& work, const std::vector<Vec3>& input, double sigma, double strength, const RiskOptions& options);

  // The input moved by ε b_i N_i at every probed vertex: where the probe's copy of each candidate starts.
  std::vector<Vec3> probedInput() const;
  // The risks of candidate x, whose copy computed from probedInput() is xp.
  Risk operator()(const std::vector<Vec3>& x, const std::vector<Vec3>& xp) const;

  int probedVertices() const { return probed_; }
  // The normal risk of the noise itself (of the input as a candidate, in expectation): σ² tr L / area,
  // with σ times the strength.
  double noiseNormalRisk() const { return area_ > 0 ? sigmaRanked_ * sigmaRanked_ * traceL_ / area_ : 0.0; }

 private:
  const Mesh& mesh_;
  const std::vector<Vec3>& input_;
  std::vector<Vec3> normals_;          // N; zero where a vertex has none (not measured)
  std::vector<signed char> probe_;     // b: ±1 at probed vertices, else 0
  std::vector<float> cot_;             // per face corner k: cot of its angle / 2, the weight of the opposite edge
  double sigma_ = 0, sigmaRanked_ = 0, eps_ = 0;
  double traceL_ = 0, area_ = 0;       // Σ_i L_ii over measured vertices; the surface's area
  int measured_ = 0, probed_ = 0;
};

}  // namespace geoshift::denoise_detail

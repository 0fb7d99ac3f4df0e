#pragma once
// The default denoiser's risk estimate (docs/denoising.md#the-risk-estimate): Stein's unbiased
// risk estimate of a candidate's error, from the candidate and the same candidate computed from a
// probed copy of the input (Monte-Carlo SURE, Ramani, Blu and Unser 2008). The error is measured
// along the normals N of a smoothed copy of the input: e_i = (x_i − x*_i)·N_i, mean of e² over the
// vertices; and the same for its differences across edges, e_i − e_j, which tilt the face normals.
#include <cstdint>
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/smoothing.hpp"

namespace geoshift::denoise_detail {

struct RiskOptions {
  int normalSmoothing = 20;  // Taubin steps of the copy that gives N
  TaubinOptions taubin;      // its λ, μ and weights (the iteration count is normalSmoothing)
  std::uint64_t seed = 1;    // of the probe's signs
  // 1: every vertex is probed (±1 each). d > 1: only vertices at least d edges apart from each other
  // (chosen greedily in index order), so that the probe's cross terms, which carry its randomness,
  // mostly vanish; the divergence is scaled up from the probed vertices to all.
  int probeSpacing = 5;
  // With the mesh renumbered (Mesh::renumber), the caller's vertex v is vertex visitOrder[v]: the
  // probe's vertices are chosen and its signs drawn in the caller's order, so the probe does not
  // depend on the renumbering. Null: index order.
  const std::vector<int>* visitOrder = nullptr;
  // Each probed vertex's divergence term kept within [0, 1]: a discrete decision (such as the
  // vertex update's flip guard) that goes one way for the input and the other for the probed copy makes
  // the difference quotient a jump of ±(step / ε), which would swing the risk by far more than the
  // candidates differ (docs/denoising.md#the-risk-estimate).
  bool boundedDivergence = true;
  // Weight of the risk of the error's differences across edges (its gradient, what tilts the face
  // normals) beside the risk of the error itself in what candidates are ranked by; 0: position alone
  // (DenoiseOptions::gradientRiskWeight).
  double gradientWeight = 0;
};

// A candidate's risk, in squared length per vertex: `ranked` with σ times the strength (what
// candidates are ranked by), `unbiased` with σ.
struct Risk {
  double position = 0, positionUnbiased = 0;
  double gradient = 0;  // the edge-difference risk, per edge over 2 (σ² for the input), ranked σ
  double ranked = 0;    // position + gradientWeight × gradient
};

// What the risk is made of, for one candidate: Σ e², the divergence and the gain
// Σ_v ((x'_v − x_v)·N_v / ε)², an estimate of tr JᵀJ (both scaled to all vertices). The risk for any
// σ follows from the first two (RiskEstimate::at), the gain serves the noise level's bound.
struct RiskSums {
  double fit = 0, div = 0, gain = 0;
  double edgeFit = 0, edgeDiv = 0;  // Σ over edges of (e_i − e_j)², and the estimate of tr(L J)
};

class RiskEstimate {
 public:
  // `work` supplies the connectivity; its positions are overwritten (the caller restores them).
  // sigma: the noise level in the mesh's units, strength: its multiplier for ranking.
  RiskEstimate(Mesh& work, const std::vector<Vec3>& input, double sigma, double strength, const RiskOptions& options);

  // The input moved by ε b_i N_i at every probed vertex: where the probe's copy of each candidate starts.
  std::vector<Vec3> probedInput() const;
  // Draws the probe's signs again from `seed`, on the same vertices: another probe of the same
  // kind, for scoring a candidate more than once.
  void reseed(std::uint64_t seed);
  // The sums of candidate x, whose copy computed from probedInput() is xp.
  RiskSums sums(const std::vector<Vec3>& x, const std::vector<Vec3>& xp) const;
  // The risk from the sums for a noise level sigma (ranked with sigma × strength).
  Risk at(const RiskSums& s, double sigma) const;
  // The noise variance at which the candidate's risk would be zero: Σ e² / (m − 2 div). Its
  // expectation is σ² plus the candidate's error over (m − 2 tr J), so the least over good
  // candidates bounds the noise from above (docs/denoising.md#the-noise-level); 0 when
  // m − 2 div <= m / 2 (a light candidate says nothing).
  double impliedVariance(const RiskSums& s) const;
  // For a linear candidate (Taubin steps alone) a tighter bound, Σ e² / (m − 2 div + gain): there
  // E Σ e² is σ² (m − 2 tr J + tr JᵀJ) plus what the smoothing takes from the clean mesh, so only
  // that part lifts it above σ². 0 when the denominator is at most m / 2.
  double linearImpliedVariance(const RiskSums& s) const;

  // N at every vertex; zero where a vertex has none (not measured).
  const std::vector<Vec3>& normals() const { return normals_; }
  double strength() const { return strength_; }
  int probedVertices() const { return probed_; }
  int measuredVertices() const { return measured_; }

 private:
  // Whether halfedge h stands for its edge (once per edge) between two measured vertices.
  bool countsEdge(int h) const;

  const Mesh& mesh_;  // the connectivity (its positions are not read)
  const std::vector<Vec3>& input_;
  std::vector<Vec3> normals_;       // N; zero where a vertex has none (not measured)
  std::vector<signed char> probe_;  // b: ±1 at probed vertices, else 0
  double sigma_ = 0, strength_ = 1, eps_ = 0;
  bool boundedDivergence_ = true;
  int measured_ = 0, probed_ = 0;
  double gradientWeight_ = 0;
  double edges_ = 0;         // between measured vertices
  double probedDegree_ = 0;  // Σ over probed vertices of their edges to measured ones
  const std::vector<int>* visitOrder_ = nullptr;  // RiskOptions::visitOrder
};

}  // namespace geoshift::denoise_detail

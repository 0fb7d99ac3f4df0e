#pragma once
// Mesh denoising (docs/denoising.md). Two pipelines share one entry point:
//  - Default: blurring mean shift of the face normals over geodesic neighbourhoods, each pass
//    followed by a vertex update; the noise level is estimated from the mesh and the amount of
//    smoothing (Taubin pre-smoothing steps, number of passes) is chosen by Stein's unbiased risk
//    estimate, so no setting depends on the mesh at hand or on a ground truth.
//  - Paper: the paper's §4.1, passes of [mean shift of the vertex normals with the kernel of eq. 8 →
//    face normals → vertex update] on a Taubin-smoothed support, kept to reproduce its figures.
#include <cstdint>
#include <functional>
#include <vector>

#include "geoshift/face_normal_shift.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/smoothing.hpp"
#include "geoshift/vertex_update.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift {

enum class DenoisePreset { Default, Paper };

// How a face's target normal comes from its three filtered vertex normals (paper preset).
enum class FaceNormalRule {
  Mean,       // the paper's: their normalised mean. A face beside a crease averages the two sides
              // its corners took and the crease is bevelled (about 45° off on a box).
  Consensus,  // their mean weighted by agreement with the face's own normal,
              // exp(−|n_k − n_f|² / 2h_r²): a corner that took the other side of a crease drops out.
};

struct PaperDenoiseOptions {
  int passes = 3;
  FaceNormalRule faceNormals = FaceNormalRule::Consensus;
  // Bandwidth of the consensus weights (chord length between unit normals); 0: the mean shift's h_r.
  double consensusBandwidth = 0.25;
  // The mean shift of the normals; `channels` is ignored. Defaults: the paper's r = 4 AEL,
  // h_s = 3 AEL, h_r = 0.45, k_max = 50, ε = AEL/5, kernel eq. 8, the sampled range update
  // (docs/denoising.md#the-paper-preset).
  MeanShiftOptions meanShift = paperMeanShift();
  TaubinOptions support;             // smoothing of the support copy (MeshLab's 10 λ|μ steps)
  VertexUpdateOptions vertexUpdate;  // 20 iterations, no face ever flipped relative to the input

  static MeanShiftOptions paperMeanShift() {
    MeanShiftOptions o;
    o.spatialBandwidth = 3;
    o.radius = 4;
    o.rangeBandwidth = 0.45;
    o.rangeKernel = RangeKernel::NormalSimilarity;
    o.maxIterations = 50;
    o.epsilon = 0.2;
    o.rangeUpdate = RangeUpdate::Sampled;
    return o;
  }
};

struct DenoiseOptions {
  DenoisePreset preset = DenoisePreset::Default;

  // --- Default preset ---
  // Noise level in average edge lengths (RMS displacement across the surface); 0: estimated from
  // the mesh (estimateNoise).
  double noiseLevel = 0;
  // Multiplies the noise level the risk estimate assumes: above 1 smooths more, below 1 less.
  double strength = 1;
  // Candidate h_r of the face normal shift (chord length between unit normals): smaller keeps more
  // edges, larger smooths organic shapes more evenly. The risk estimate picks one.
  std::vector<double> rangeBandwidths = {0.35, 0.5};
  FaceNeighborhoodOptions neighborhood;  // r = 1.75 AEL, h_s = 0.6 AEL, on the support
  TaubinOptions supportSmoothing;        // the support the neighbourhoods are found on (10 steps)
  // Candidate Taubin steps before the passes; the risk estimate picks one (and its pass count).
  // The candidates race: one clearly behind the leader stops early (docs/denoising.md#the-default-pipeline).
  std::vector<int> presmoothing = {3, 15};
  // Taubin-only candidates: the input smoothed by candidateTaubin to each of these step counts
  // (ascending), each scored once and never followed by passes. candidateTaubin's μ −0.502 puts the
  // pass band near zero, so that many steps do not swell the low frequencies as MeshLab's μ −0.53
  // does. One wins only when it ranks taubinOnlyMargin (in units of σ²) below the best candidate
  // with passes: a feature-preserving candidate of nearly the same risk along the normals keeps
  // better normals (docs/denoising.md#taubin-only-candidates). Empty: none.
  std::vector<int> taubinOnlySteps = {5, 8, 12, 18, 27, 40, 60, 90};
  TaubinOptions candidateTaubin = [] {
    TaubinOptions t;
    t.mu = -0.502;
    return t;
  }();
  double taubinOnlyMargin = 0.005;
  // A light start for thin and very uneven parts (docs/denoising.md#a-light-start): where the
  // Taubin-only ladder ranks least at its first rung (at the race's level) and
  // the input's highest frequencies have a kurtosis of at most impulseSpectrumKurtosis, a third
  // start of lightStart Taubin steps races beside the others, at every h_r. Its winner stands only
  // if its face normals turn across an edge (meanNormalTurn) at most lightStartTurn times as much
  // as those of the best candidate of the other starts and Taubin alone; otherwise that candidate
  // wins and the light start takes no part in the tie or the blend. 0: never.
  int lightStart = 1;
  double lightStartTurn = 1.5;
  // The blend of least risk (docs/denoising.md#the-blend-of-least-risk). With errors e_W, e_O along
  // N, the blend (1 − w) x_W + w x_O has the risk (1 − w) R_W + w R_O − w (1 − w) D, D their mean
  // squared difference along N over σ²: least at w = 0.5 (1 − (R_O − R_W) / D). The winner is so
  // blended with the best candidate of the other family (Taubin alone against a start with
  // passes), and then with the best candidate with passes from the other start, each against the
  // blend so far. blendSpread scales D in that weight (1: the risk's own optimum; larger blends
  // across larger gaps); 0: never. Within [0, 1000].
  double blendSpread = 1;
  int maxPasses = 40;
  int patience = 4;         // stop a candidate after this many passes without a lower risk
  int fixedPasses = 0;      // > 0: no risk estimate, presmoothing[0] steps and exactly this many passes
  int vertexIterations = 10;
  std::uint64_t seed = 1;   // of the risk estimate's random probe
  // The risk estimate measures each vertex's error along a normal: that of a copy of the input
  // smoothed by this many Taubin steps (0: the noisy input's own normals, which point off by
  // about the noise's angle). More steps than the pre-smoothing candidates take, so that the
  // directions do not share a candidate's noise (docs/denoising.md#the-risk-estimate).
  int riskNormalSmoothing = 20;
  // The probe of the risk estimate: 1 probes every vertex; d > 1 only vertices at least d edges apart,
  // whose divergence is scaled up to all: fewer of the probe's cross terms, whose signs are its
  // randomness (docs/denoising.md#the-risk-estimate).
  int probeSpacing = 5;
  // Each probed vertex's part of the divergence is kept within [0, 1], the range of a smoother's
  // derivative at its own vertex: a larger one comes from a discrete decision (such as the flip guard's) that
  // went one way for the input and the other for the probe, a jump that would swing the risk
  // (docs/denoising.md#the-risk-estimate). false: the raw difference quotient.
  bool boundedDivergence = true;
  // Candidates are ranked by the risk of their error along N plus gradientRiskWeight × the risk of
  // its differences across edges (what tilts the face normals), each estimated the same way. 0, the
  // default: the error along N alone (0.15 won a case on the tuning set and lost two on the
  // validation set; docs/denoising.md#the-errors-differences-across-edges).
  double gradientRiskWeight = 0;
  // A tie between starts: when the best candidates of two or more pre-smoothing step counts rank
  // within tieMargin of the leader's (in units of σ², as the race ranks), each is scored again with
  // up to tieProbes more probes (other signs on the same vertices) and the one of least mean rank
  // wins; the probes stop once the leader's lead is tieStandardErrors standard errors. One probe's
  // spread would otherwise let the seed decide between candidates of very different normals
  // (docs/denoising.md#ties-between-starts). tieProbes 0: never.
  int tieProbes = 4;
  double tieMargin = 0.01;
  double tieStandardErrors = 4;  // the lead, in standard errors of the difference, that settles it
  // When the probes run out with no contender that far ahead, those the leader does not lead by
  // that much are tied along N, which cannot tell their normals apart: the one whose face normals
  // turn least across an edge on average (the normal field's total variation, meanNormalTurn) wins
  // (docs/denoising.md#ties-between-starts). false: the leader by mean rank, however slight its lead.
  bool tieByNormals = true;
  // The input itself is a candidate: it moves nothing, so its risk is the noise's, σ², exactly (no
  // error to fit, a divergence of one a vertex). Where no other candidate ranks below it, the input
  // is returned as it was, and the outlier correction does not run: on a clean or already denoised
  // mesh every candidate takes more of the shape than of the noise, and the correction would take
  // its creases and corners, which stand out like outliers, for the noise. Not where the correction
  // is asked for in any case (impulseKurtosis 0) (docs/denoising.md#the-input-as-a-candidate).
  // false: the best of the others, always.
  bool inputCandidate = true;
  // Where at least 1% of the mesh's adjacencies (the two vertices of an edge, the two faces across
  // it) lie more than 4096 indices apart and the Morton order of the positions (spatialOrder in
  // mesh.hpp) halves that share, the passes run with the vertices and faces renumbered in it, so that
  // neighbourhoods read nearby memory, and the result is put back in the caller's order. The probe is
  // drawn in the caller's order either way, so the result differs only by the order of
  // floating-point sums (docs/denoising.md#speed-and-memory). false: the caller's order always.
  bool spatialOrder = true;
  // With an estimated noise level: the race ranks with the estimate's upper level, then the level is
  // refined from the candidates (the least variance a good one implies) and they are ranked again
  // (docs/denoising.md#the-noise-level).
  bool refineNoise = true;
  // In that refinement, where the Taubin-alone candidates' tighter bound (linear smoothing: the noise
  // it removes is known from its derivative) puts the noise level below detailBoundRatio × the
  // general bound's, the estimate has read the mesh's detail as noise and the tighter bound is
  // used; closer than that, a slightly high level smooths the normals more, which pays
  // (docs/denoising.md#the-noise-level). 0: never.
  double detailBoundRatio = 0.9;
  // With refineNoise, the level the candidates are finally ranked with is instead read from the
  // input's highest frequencies (highFrequencyNoiseLevel in noise.hpp: a plain mean away from creases,
  // right for any distribution of the noise, where the quadric estimate's lower half reads
  // fixed-magnitude noise high and detail as noise), times levelLean: a level a little high smooths
  // the normals a little more, which pays. The reported level is the one read
  // (docs/denoising.md#the-noise-level). false, or where no vertex is three rings from a crease or a
  // boundary: the level refined from the candidates, as above.
  bool highFrequencyLevel = true;
  double levelLean = 1.1;
  // Where fewer than highFrequencyMinSamples vertices lie three rings from every crease and boundary
  // (HighFrequencyNoise::samples), the reading r of n vertices is a guess: the level is then
  // exp(w ln r + (1 − w) ln ρ), ρ the level refined from the candidates, w = n / (n + 5) (the
  // reading's relative variance about 1 / 2n against the refined level's about 0.1), ranked with
  // levelLean^w; and the reading's kurtosis does not trigger the impulse correction
  // (docs/denoising.md#the-noise-level, "A reading of few vertices"). 0: the reading always.
  int highFrequencyMinSamples = 50;
  // Where the spectrum reads fewer than highFrequencyMinSamples vertices and at least
  // planarLevelShare of the faces lie in the plane of a face across an edge (planarNoise in
  // noise.hpp: a part of flat faces that the noise left mostly where they were), the level is read
  // against those planes instead, ranked with levelLean (docs/denoising.md#the-noise-level, "Planes
  // left untouched"). 0: never.
  double planarLevelShare = 0.5;
  // After the impulse correction, on a part of flat faces (the input confirms at least
  // planarLevelShare of its faces, planarNoise in noise.hpp), a vertex the noise left where it was
  // keeps its input position: one within planarKeep × the noise level of the nearest untouched
  // plane of its two-ring, in the plane of the face across the edge opposite it in one of its faces,
  // and each of whose faces off its neighbours' planes holds another vertex that does not fit so
  // (docs/denoising.md#impulsive-noise, "Vertices on untouched planes"). 0: never.
  double planarKeep = 0.1;
  // The race keeps the better half of its runs every `patience` passes (docs/denoising.md#the-race).
  bool halvingRace = true;
  // Impulsive noise (a few vertices moved far, the rest not at all): when the kurtosis of the
  // winner's displacement along N exceeds impulseKurtosis (Gaussian noise: about 3), each vertex
  // is weighted by w = max(0, 1 − τ²/d²), d its displacement (a non-negative garrote), and moves w
  // of the way to the winner's position plus the detail the winner took from its neighbours, each
  // neighbour trusted by 1 − w: the outliers are corrected, the vertices the noise left alone stay
  // where they are (docs/denoising.md#impulsive-noise). τ = impulseShrink × 1.4826 median |d|, the
  // displacements' robust spread (what the winner did to the vertices the noise did not touch).
  // impulseShrink 0: never; impulseKurtosis 0: whenever the winner moved anything (a kurtosis is at
  // least 1).
  double impulseKurtosis = 6;
  double impulseShrink = 2;
  // The correction also runs when the kurtosis of the input's highest frequencies
  // (HighFrequencyNoise::kurtosis in noise.hpp, which does not depend on the winner) exceeds
  // impulseSpectrumKurtosis: detail can hide outliers from the winner's displacement
  // (docs/denoising.md#impulsive-noise). 0: the winner's kurtosis alone.
  double impulseSpectrumKurtosis = 5.5;
  // The spectrum's trigger needs a reading of at least impulseSpectrumMinSamples vertices
  // (HighFrequencyNoise::samples): with n read, Gaussian noise's kurtosis has a standard error of about
  // √(24 / n), and at 100 the trigger stands three of them above Gaussian noise in random directions
  // (about 4). Below, the winner's kurtosis must say so too (docs/denoising.md#the-noise-level, "The
  // spectrum alone, from few vertices"). 0: any reading of at least highFrequencyMinSamples.
  int impulseSpectrumMinSamples = 100;
  // The winner's kurtosis reads the mesh's own irregular triangles as well as outliers: its trigger
  // is vetoed where the spectrum, read from at least highFrequencyMinSamples vertices, says the
  // noise is lighter-tailed than Gaussian noise in random directions with two standard errors to
  // spare, kurtosis + 2 √(24 / n) < impulseSpectrumVeto (docs/denoising.md#the-noise-level,
  // "A reading of few vertices"). Never where impulseKurtosis is 0 (the correction asked for in any
  // case). 0: never vetoed.
  double impulseSpectrumVeto = 4;
  int threads = 0;          // 0: all hardware threads; results do not depend on it
  // Called for every candidate scored, with its Taubin steps, passes, positions and unbiased risk
  // (mean squared error along the normals): for evaluations and diagnostics. The positions are the
  // whole mesh's in the caller's vertex order: small pieces at their input positions, and with
  // levels > 0 the fine mesh synthesized from the coarse candidate.
  std::function<void(int steps, int passes, const std::vector<Vec3>& positions, double risk)> onCandidate;

  // --- Paper preset ---
  PaperDenoiseOptions paper;

  // --- Both ---
  // Pieces (vertices joined through faces) of fewer vertices keep their positions: at a few edges
  // across, a piece's whole shape is at the frequencies smoothing removes (a tetrahedron collapses
  // to a point, a fin cut off a non-manifold edge to a sliver), and their displacements would read
  // as impulsive noise to the rest of the mesh (docs/denoising.md#small-pieces). 0: every piece is
  // denoised.
  int minPieceVertices = 50;

  // --- Both: hybrid denoising (Algorithm 2 on positions) ---
  // Analyse `levels` wavelet levels, denoise the coarse mesh, synthesise with detail gain `alpha`
  // (one for all levels or one per level; 0 drops the fine details with their noise).
  int levels = 0;
  std::vector<double> alpha = {0};
  WaveletOptions wavelet;
};

struct DenoiseResult {
  // Default preset
  double noiseLevel = 0;        // used, in average edge lengths (after `strength`)
  bool noiseEstimated = false;  // from the mesh (noiseLevel option 0)
  int presmoothingSteps = 0;    // chosen
  bool taubinOnly = false;      // the winner is presmoothingSteps of candidateTaubin, no pass (passes 0)
  double rangeBandwidth = 0;    // chosen
  int passes = 0;               // chosen
  int passesRun = 0;            // computed, all candidates (and the probes of a tie)
  int tieProbes = 0;            // more probes run to settle a tie between starts (tieProbes option)
  bool tieByNormals = false;    // they left it tied along N, and the normals' turn decided (tieByNormals)
  bool lightStartRaced = false;     // the light start raced beside the others (lightStart)
  bool lightStartTurnedDown = false;  // its winner's normals turned too much: the best of the rest won
  double displacementKurtosis = 0;  // of the winner's displacement along N (impulseKurtosis)
  double spectrumKurtosis = 0;      // of the input's highest frequencies (impulseSpectrumKurtosis); 0: not read
  bool impulseGarrote = false;  // the outliers were corrected as for impulsive noise (impulseShrink)
  bool keptInput = false;       // no candidate ranked below the input: returned as it was (inputCandidate)
  bool planarLevel = false;     // the level was read against the planes the noise left (planarLevelShare)
  int planarKept = 0;           // vertices the impulse correction had moved, back at their input positions (planarKeep)
  // The candidates blended in (blendSpread), each with its weight in the mix it joined (0: none;
  // then the other fields are 0): `blend`, the other family's, mixed with the winner; `startBlend`,
  // the other start's, mixed with that. The result is (1 − s) ((1 − b) x_W + b x_O) + s x_S for the
  // weights b and s. The fields above describe the winner.
  struct Blend {
    double weight = 0;
    int presmoothingSteps = 0;
    bool taubinOnly = false;
    double rangeBandwidth = 0;
    int passes = 0;
  } blend, startBlend;
  double estimatedError = 0;    // risk estimate of the result: RMS error across the surface, in AEL;
                                // 0 when below a tenth of the noise level (not resolved)
  size_t neighborhoodBytes = 0;
  // The passes ran in spatial order (DenoiseOptions::spatialOrder); the share of the mesh's
  // adjacencies more than 4096 indices apart in the caller's order (0 when not measured).
  bool spatialOrder = false;
  double farAdjacencies = 0;
  // Paper preset
  double meanIterations = 0;     // of the mean shift, per vertex per pass
  double convergedFraction = 0;  // of the last pass
  // Both
  int keptPieces = 0;            // pieces below minPieceVertices, left as they were
  int keptVertices = 0;          // their vertices
  int limitedSteps = 0;          // vertex-update steps the flip guard shortened, all passes
  int threads = 1;
  int filteredVertices = 0;      // the mesh's, or the coarse mesh's with levels > 0
  double seconds = 0;
};

// Moves the mesh's vertices. Throws InputError naming the option on bad options and on a mesh
// without faces; Cancelled through `progress`, leaving the mesh as it was.
DenoiseResult denoise(Mesh& mesh, const DenoiseOptions& options = {}, const Progress& progress = {});

}  // namespace geoshift

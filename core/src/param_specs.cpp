// The parameter tables of every op (params.hpp; docs/architecture.md#parameters). Defaults come from
// the options structs' initialisers; ranges are what the core accepts, with upper bounds on counts
// and lengths that keep a typo from running for hours.
#include <limits>
#include <string>

#include "geoshift/bilateral_normal.hpp"
#include "geoshift/check.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/error.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/hybrid.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/params.hpp"
#include "geoshift/smoothing.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxSafeInteger = 9007199254740991.0;  // 2^53 - 1: seeds must survive a JS number

// Builds one ParamSpec line by line, so that the tables below read as tables.
class P {
 public:
  P(std::string name, ParamType type, std::string doc) {
    s_.name = std::move(name);
    s_.type = type;
    s_.doc = std::move(doc);
  }
  P& byDefault(ParamValue v) {
    s_.defaultValue = std::move(v);
    return *this;
  }
  P& range(double min, double max) {
    s_.min = min;
    s_.max = max;
    return *this;
  }
  // (0, max]: the vocabulary's "must be > 0".
  P& positive(double max = kInf) {
    range(0, max);
    s_.minExclusive = true;
    return *this;
  }
  P& choices(std::vector<std::string> values) {
    s_.values = std::move(values);
    return *this;
  }
  P& list() {
    s_.list = true;
    return *this;
  }
  P& appliesWhen(ParamCondition c) {
    s_.appliesWhen.push_back(std::move(c));
    return *this;
  }
  P& inCase(ParamCondition when, std::optional<ParamValue> value, std::optional<double> min = {},
            std::optional<double> max = {}) {
    s_.cases.push_back({std::move(when), std::move(value), min, max});
    return *this;
  }
  P& cli(std::string name) {
    s_.cli = std::move(name);
    return *this;
  }
  ParamSpec take() { return std::move(s_); }

 private:
  ParamSpec s_;
};

using T = ParamType;

// The parameters moved into a vector one by one (an initializer list would copy each of them).
template <class... Params>
std::vector<ParamSpec> table(Params&&... params) {
  std::vector<ParamSpec> out;
  out.reserve(sizeof...(params));
  (out.push_back(params.take()), ...);
  return out;
}

ParamValue numbers(const std::vector<int>& v) { return std::vector<double>(v.begin(), v.end()); }

OpParamSpecs noiseSpecs() {
  const NoiseOptions d;
  return {"noise",
          "Seeded synthetic displacement of the vertices (as `geoshift noise`)",
          table(
              P("amount", T::Number, "magnitude in multiples of the average edge length (AEL)").byDefault(d.amount).range(0, 100),
              P("distribution", T::Enum,
                "fixed: |d| = amount AEL; uniform: |d| in [0, amount AEL]; gaussian: sigma = amount AEL; impulsive: "
                "a tenth of the vertices, sigma = amount AEL")
                  .choices({"fixed", "uniform", "gaussian", "impulsive"}).byDefault(std::string("fixed")).cli("dist"),
              P("direction", T::Enum, "random: a uniformly random direction; normal: along the vertex normal")
                  .choices({"random", "normal"}).byDefault(std::string("random")),
              P("seed", T::Integer, "random seed: the same seed gives the same noise natively and in wasm")
                  .byDefault(static_cast<double>(d.seed)).range(0, kMaxSafeInteger))};
}

OpParamSpecs smoothSpecs() {
  const TaubinOptions d;
  return {"smooth",
          "Taubin lambda|mu smoothing of the positions (as `geoshift smooth`)",
          table(
              P("iterations", T::Integer, "lambda|mu step pairs").byDefault(static_cast<double>(d.iterations)).range(0, 1e6),
              P("lambda", T::Number, "shrinking step, > 0").byDefault(d.lambda).range(-10, 10),
              P("mu", T::Number, "inflating step, < -lambda").byDefault(d.mu).range(-10, 10),
              P("weights", T::Enum, "Laplacian weights: uniform, fujiwara (1/length), cotangent")
                  .choices({"uniform", "fujiwara", "cotangent"}).byDefault(std::string("uniform")),
              P("threads", T::Integer, "worker threads (0 = all); results do not depend on it")
                  .byDefault(static_cast<double>(d.parallel.threads)).range(0, 1024))};
}

OpParamSpecs curvatureSpecs() {
  return {"curvature",
          "Discrete curvature as the scalar _CURVATURE and its color map (as `geoshift curvature`)",
          table(
              P("kind", T::Enum, "abs = |k1|+|k2| (MeshLab), mean H, gauss K, rms")
                  .choices({"abs", "mean", "gauss", "rms"}).byDefault(std::string("abs")))};
}

OpParamSpecs geodesicSpecs() {
  return {"geodesic",
          "Geodesic distance from a vertex as the scalar _GEODESIC, -1 beyond the radius (as `geoshift geodesic`)",
          table(
              P("source", T::Integer, "the source vertex (an index of the mesh as loaded)").byDefault(0.0).range(0, kInf),
              P("radius", T::Number, "stop at this geodesic distance, in AEL (default: the whole mesh)").positive())};
}

OpParamSpecs filterSpecs() {
  const MeanShiftOptions d;
  const HybridOptions h;
  return {"filter",
          "Riemannian mean shift (mode ms) or blurring mean shift (bms) of a vertex signal; the hybrid filter "
          "with levels > 0 (as `geoshift filter`)",
          table(
              P("signal", T::Text,
                "color, normal, curvature, terrain, or attribute names, several separated by commas")
                  .byDefault(std::string("color")),
              P("mode", T::Enum, "ms = one pass (mean shift), bms = blurring passes; unset: passes alone decide")
                  .choices({"ms", "bms"}),
              P("passes", T::Integer, "number of passes (more than 1: blurring mean shift)")
                  .byDefault(static_cast<double>(d.passes)).range(1, 10000).inCase({{"mode", {"bms"}}}, 10.0),
              P("hs", T::Number, "spatial bandwidth h_s in AEL").byDefault(d.spatialBandwidth).positive(1e6),
              P("hr", T::Number,
                "range bandwidth h_r in the signal's units (default: color 0.1, normal 0.45, otherwise a tenth of "
                "the signal's 10-90% spread)")
                  .positive(1e12),
              P("radius", T::Number, "truncation radius r in AEL; 0: 3 h_s").byDefault(d.radius).range(0, 1e6),
              P("kmax", T::Integer, "most iterations per pass").byDefault(static_cast<double>(d.maxIterations)).range(1, 1e6),
              P("eps", T::Number, "stop when a step is shorter than this, in AEL").byDefault(d.epsilon).positive(1e6),
              P("rangeUpdate", T::Enum,
                "joint: the range value moves with its own mean shift step; sampled (the paper): it is read from "
                "the signal at the iterate")
                  .choices({"joint", "sampled"}).byDefault(std::string("joint")),
              P("segments", T::Boolean, "also label vertices by their modes (scalar _SEGMENT)").byDefault(false),
              P("threads", T::Integer, "worker threads (0 = all); results do not depend on it")
                  .byDefault(static_cast<double>(d.parallel.threads)).range(0, 1024),
              P("levels", T::Integer, "wavelet levels: filter a coarse approximation and restore the details (Algorithm 2)")
                  .byDefault(static_cast<double>(h.levels)).range(0, kInf),
              P("alpha", T::Number,
                "detail gain per level, finest first, or one for all: 1 restores the details, 0 drops them, > 1 enhances")
                  .list().byDefault(h.alpha).range(-kInf, kInf),
              P("filterGeometry", T::Boolean, "with levels: the gains apply to the positions too").byDefault(h.filterGeometry))};
}

OpParamSpecs denoiseSpecs() {
  const DenoiseOptions d;
  const PaperDenoiseOptions& paper = d.paper;
  const MeanShiftOptions& ms = paper.meanShift;
  const BilateralNormalOptions b;
  const TaubinOptions t;
  const ParamCondition meanShift = {{"method", {"meanshift"}}};
  const ParamCondition ours = {{"method", {"meanshift"}}, {"preset", {"default"}}};
  const ParamCondition paperPreset = {{"method", {"meanshift"}}, {"preset", {"paper"}}};
  const ParamCondition bilateral = {{"method", {"bilateral"}}};
  const ParamCondition taubin = {{"method", {"taubin"}}};
  return {"denoise",
          "Vertex positions denoised, keeping sharp features (as `geoshift denoise`; docs/denoising.md)",
          table(
              P("method", T::Enum,
                "meanshift: mean shift of the normals, then the vertex update (preset default or paper); bilateral: "
                "bilateral normal filtering (Zheng et al. 2011), then the vertex update; taubin: Taubin lambda|mu "
                "smoothing (not feature-preserving; a baseline)")
                  .choices({"meanshift", "bilateral", "taubin"}).byDefault(std::string("meanshift")),
              P("preset", T::Enum,
                "default: face-normal mean shift, the amount of smoothing chosen by SURE from the estimated noise; "
                "paper: the paper's 4.1 pipeline")
                  .choices({"default", "paper"}).byDefault(std::string("default")).appliesWhen(meanShift),
              P("noise", T::Number, "noise level in AEL (0: estimate it from the mesh)")
                  .byDefault(d.noiseLevel).range(0, 1e6).appliesWhen(ours),
              P("strength", T::Number, "times the noise level; above 1 smooths more, below 1 less")
                  .byDefault(d.strength).positive(1e6).appliesWhen(ours),
              P("hs", T::Number, "spatial bandwidth h_s in AEL")
                  .byDefault(d.neighborhood.spatialBandwidth).positive(1e6).appliesWhen(meanShift)
                  .inCase(paperPreset, ms.spatialBandwidth),
              P("hr", T::Number,
                "range bandwidth h_r between unit normals; smaller keeps more edges (preset default: candidates SURE picks from; 0: those)")
                  .list().byDefault(d.rangeBandwidths).range(0, 1e6).appliesWhen(meanShift)
                  .inCase(paperPreset, ms.rangeBandwidth),
              P("radius", T::Number, "neighbourhood radius in AEL")
                  .byDefault(d.neighborhood.radius).positive(1e6).appliesWhen(meanShift)
                  .inCase(paperPreset, ms.radius),
              P("passes", T::Integer,
                "passes of normal filtering and vertex update (preset default: 0 lets SURE choose, more fixes the count)")
                  .byDefault(static_cast<double>(d.fixedPasses)).range(0, 10000).appliesWhen(meanShift)
                  .inCase(paperPreset, static_cast<double>(paper.passes), 1, 10000),
              P("presmoothing", T::Integer, "candidate Taubin step counts before the passes; SURE picks one")
                  .list().byDefault(numbers(d.presmoothing)).range(0, 10000).appliesWhen(ours),
              P("taubinOnly", T::Integer,
                "Taubin step counts (mu " + formatNumber(d.candidateTaubin.mu) +
                    ") scored as candidates of their own, without passes; 0: none")
                  .list().byDefault(numbers(d.taubinOnlySteps)).range(0, 10000).appliesWhen(ours),
              P("lightStart", T::Integer,
                "Taubin steps of a light start, raced beside the others where the Taubin-only candidates estimate "
                "least at their fewest steps (thin parts); its winner stands only if its normals turn at most " +
                    formatNumber(d.lightStartTurn) + " times as much as the rest's; 0: none")
                  .byDefault(static_cast<double>(d.lightStart)).range(0, 10000).appliesWhen(ours),
              P("impulse", T::Enum,
                "outliers of impulsive noise: auto: corrected when the result's displacements or the input's highest "
                "frequencies say the noise moved few vertices far; on: always corrected, the other vertices mostly "
                "kept; off: never")
                  .choices({"auto", "on", "off"}).byDefault(std::string("auto")).appliesWhen(ours),
              P("maxPasses", T::Integer, "most passes SURE considers")
                  .byDefault(static_cast<double>(d.maxPasses)).range(1, 10000).appliesWhen(ours),
              P("patience", T::Integer, "stop a candidate after this many passes without a lower risk")
                  .byDefault(static_cast<double>(d.patience)).range(1, 10000).appliesWhen(ours),
              P("seed", T::Integer, "seed of the risk estimate's random probe")
                  .byDefault(static_cast<double>(d.seed)).range(0, kMaxSafeInteger).appliesWhen(ours),
              P("kmax", T::Integer, "most mean shift iterations per vertex and pass")
                  .byDefault(static_cast<double>(ms.maxIterations)).range(1, 1e6).appliesWhen(paperPreset),
              P("eps", T::Number, "stop when a mean shift step is shorter than this, in AEL")
                  .byDefault(ms.epsilon).positive(1e6).appliesWhen(paperPreset),
              P("rangeUpdate", T::Enum, "sampled (the paper) or joint")
                  .choices({"sampled", "joint"})
                  .byDefault(std::string(ms.rangeUpdate == RangeUpdate::Sampled ? "sampled" : "joint"))
                  .appliesWhen(paperPreset),
              P("faceNormals", T::Enum,
                "consensus: corners that disagree with the face drop out; mean: the paper's plain mean")
                  .choices({"consensus", "mean"})
                  .byDefault(std::string(paper.faceNormals == FaceNormalRule::Mean ? "mean" : "consensus"))
                  .appliesWhen(paperPreset),
              P("supportIterations", T::Integer, "Taubin steps of the smoothed copy that carries the log and exp maps")
                  .byDefault(static_cast<double>(paper.support.iterations)).range(0, 10000).appliesWhen(paperPreset),
              P("exactCharts", T::Boolean, "a fresh log map at every iteration (slower reference)")
                  .byDefault(ms.tuning.exactCharts).appliesWhen(paperPreset),
              P("doubleWeights", T::Boolean, "kernel weights in double precision (slower reference)")
                  .byDefault(!ms.tuning.singlePrecisionKernel).appliesWhen(paperPreset),
              P("threads", T::Integer, "worker threads (0 = all); results do not depend on it")
                  .byDefault(static_cast<double>(d.threads)).range(0, 1024)
                  .appliesWhen({{"method", {"meanshift", "taubin"}}}),
              P("minPiece", T::Integer,
                "pieces (parts not joined to the rest by faces) of fewer vertices keep their positions: too small "
                "to tell noise from shape; 0: every piece is denoised")
                  .byDefault(static_cast<double>(d.minPieceVertices)).range(0, 1e9).appliesWhen(meanShift),
              P("levels", T::Integer, "wavelet levels: denoise the coarse mesh and restore the details times alpha")
                  .byDefault(static_cast<double>(d.levels)).range(0, kInf).appliesWhen(meanShift),
              P("alpha", T::Number, "detail gain per level, finest first, or one for all")
                  .list().byDefault(d.alpha).range(-kInf, kInf).appliesWhen(meanShift),
              P("normalIterations", T::Integer, "normal filtering iterations")
                  .byDefault(static_cast<double>(b.normalIterations)).range(0, 10000).appliesWhen(bilateral),
              P("sigmaC", T::Number, "spatial sigma in AEL; 0: the mean distance of adjacent face centroids")
                  .byDefault(b.sigmaSpatial).range(0, 1e6).appliesWhen(bilateral),
              P("sigmaS", T::Number, "range sigma on normal differences")
                  .byDefault(b.sigmaRange).positive(1e6).appliesWhen(bilateral),
              P("neighbors", T::Enum, "faces sharing a vertex or an edge")
                  .choices({"vertex", "edge"})
                  .byDefault(std::string(b.neighborhood == FaceNeighborhood::Edge ? "edge" : "vertex"))
                  .appliesWhen(bilateral),
              P("vertexIterations", T::Integer, "vertex update iterations per pass")
                  .byDefault(static_cast<double>(d.vertexIterations)).range(1, 10000)
                  .appliesWhen({{"method", {"meanshift", "bilateral"}}})
                  .inCase(paperPreset, static_cast<double>(paper.vertexUpdate.iterations), 0, 10000)
                  .inCase(bilateral, static_cast<double>(b.vertexUpdate.iterations), 0, 10000),
              P("fixedBoundary", T::Boolean, "keep boundary vertices in place")
                  .byDefault(paper.vertexUpdate.fixedBoundary).appliesWhen(paperPreset).appliesWhen(bilateral),
              P("flipGuard", T::Enum,
                "input: no face ends up flipped relative to the input; input-or-target: faces the noise folded may unfold")
                  .choices({"input", "input-or-target"})
                  .byDefault(std::string(paper.vertexUpdate.flipGuard == FlipGuard::InputOrTarget ? "input-or-target" : "input"))
                  .appliesWhen(paperPreset).appliesWhen(bilateral),
              P("iterations", T::Integer, "Taubin lambda|mu step pairs")
                  .byDefault(static_cast<double>(t.iterations)).range(0, 1e6).appliesWhen(taubin).cli("taubin-iterations"),
              P("lambda", T::Number, "Taubin shrinking step, > 0").byDefault(t.lambda).range(-10, 10).appliesWhen(taubin),
              P("mu", T::Number, "Taubin inflating step, < -lambda").byDefault(t.mu).range(-10, 10).appliesWhen(taubin))};
}

OpParamSpecs waveletSpecs() {
  const WaveletOptions d;
  return {"wavelet",
          "Multiresolution smoothing (alpha < 1) or enhancement (alpha > 1) of the positions and colors (as "
          "`geoshift wavelet`)",
          table(
              P("levels", T::Integer, "analysis levels (each removes about a quarter of the vertices)")
                  .byDefault(static_cast<double>(d.levels)).range(0, kInf),
              P("alpha", T::Number,
                "detail gain, one for all levels or one per level, finest first: 0 removes the details, 1 keeps "
                "them, > 1 enhances")
                  .list().byDefault(std::vector<double>{0}).range(-kInf, kInf),
              P("positionsOnly", T::Boolean, "leave the vertex colors as they are").byDefault(false))};
}

}  // namespace

const std::vector<OpParamSpecs>& paramSpecs() {
  static const std::vector<OpParamSpecs> tables = [] {
    std::vector<OpParamSpecs> all;
    for (OpParamSpecs (*make)() : {noiseSpecs, smoothSpecs, curvatureSpecs, geodesicSpecs, filterSpecs, denoiseSpecs, waveletSpecs})
      all.push_back(make());
    return all;
  }();
  return tables;
}

const OpParamSpecs& paramSpecsOf(std::string_view op) {
  std::string known;
  for (const OpParamSpecs& s : paramSpecs()) {
    if (s.op == op) return s;
    known += (known.empty() ? "" : ", ") + s.op;
  }
  throw InputError("unknown op \"" + std::string(op) + "\" (known: " + known + ")");
}

}  // namespace geoshift

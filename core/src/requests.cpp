// What requests of the smaller ops mean (requests.hpp). Choices are spelled as in their tables.
#include "geoshift/requests.hpp"

namespace geoshift {

NoiseOptions noiseOptions(const ParamRequest& r) {
  NoiseOptions o;
  o.amount = r.number("amount");
  const std::string distribution = r.text("distribution");
  o.distribution = distribution == "uniform"     ? NoiseDistribution::Uniform
                   : distribution == "gaussian"  ? NoiseDistribution::Gaussian
                   : distribution == "impulsive" ? NoiseDistribution::Impulsive
                                                 : NoiseDistribution::Fixed;
  o.direction = r.text("direction") == "normal" ? NoiseDirection::Normal : NoiseDirection::Random;
  o.seed = static_cast<std::uint64_t>(r.integer64("seed"));
  return o;
}

TaubinOptions smoothOptions(const ParamRequest& r) {
  TaubinOptions o;
  o.iterations = r.integer("iterations");
  // The table bounds λ and μ; taubinSmooth checks their relation and names the problem.
  o.lambda = r.number("lambda");
  o.mu = r.number("mu");
  const std::string weights = r.text("weights");
  o.weights = weights == "fujiwara"    ? LaplacianWeights::Fujiwara
              : weights == "cotangent" ? LaplacianWeights::Cotangent
                                       : LaplacianWeights::Uniform;
  o.parallel.threads = r.integer("threads");
  return o;
}

CurvatureKind curvatureKind(const ParamRequest& r) {
  const std::string kind = r.text("kind");
  return kind == "mean" ? CurvatureKind::Mean : kind == "gauss" ? CurvatureKind::Gaussian : kind == "rms" ? CurvatureKind::Rms : CurvatureKind::Absolute;
}

WaveletRequest waveletRequest(const ParamRequest& r) {
  WaveletRequest w;
  w.options.levels = r.integer("levels");
  w.alpha = r.numbers("alpha");
  w.positionsOnly = r.flag("positionsOnly");
  return w;
}

}  // namespace geoshift

// op "smooth": Taubin λ|μ smoothing of the positions, as `geoshift smooth`.
#include "geoshift/smoothing.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runSmooth(const OpContext& context) {
  const Params& p = context.params;
  TaubinOptions options;
  options.iterations = p.integer("iterations", options.iterations, 0, 1000000);
  // The core checks the λ/μ relation and names the problem; here only finiteness and sign ranges.
  options.lambda = p.number("lambda", options.lambda, -10, 10);
  options.mu = p.number("mu", options.mu, -10, 10);
  const std::string weights = p.choice("weights", "uniform", {"uniform", "fujiwara", "cotangent"});
  options.weights = weights == "fujiwara"    ? LaplacianWeights::Fujiwara
                    : weights == "cotangent" ? LaplacianWeights::Cotangent
                                             : LaplacianWeights::Uniform;

  Mesh mesh = context.session.build.mesh;
  taubinSmooth(mesh, options, context.progress);
  OpOutput out;
  out.positions = mesh.positions();
  out.stats.set("iterations", options.iterations);
  return out;
}

}  // namespace geoshift::wasm

// op "noise": seeded synthetic displacement for demos (same seed, same noise as `geoshift noise`).
#include <cmath>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runNoise(const OpContext& context) {
  const Params& p = context.params;
  NoiseOptions options;
  options.amount = p.number("amount", options.amount, 0, 100);
  const std::string distribution = p.choice("distribution", "fixed", {"fixed", "uniform", "gaussian", "impulsive"});
  options.distribution = distribution == "uniform"     ? NoiseDistribution::Uniform
                         : distribution == "gaussian"  ? NoiseDistribution::Gaussian
                         : distribution == "impulsive" ? NoiseDistribution::Impulsive
                                                       : NoiseDistribution::Fixed;
  options.direction = p.choice("direction", "random", {"random", "normal"}) == "normal" ? NoiseDirection::Normal
                                                                                        : NoiseDirection::Random;
  // Seeds beyond 2^53 would not survive the trip through a JS number.
  const double seed = p.number("seed", 1, 0, 9007199254740991.0);
  if (seed != std::floor(seed)) throw InputError("noise: parameter seed must be a whole number");
  options.seed = static_cast<std::uint64_t>(seed);

  context.progress.step(0, "adding noise");
  Mesh mesh = context.session.build.mesh;
  const std::vector<Vec3> displacement = addNoise(mesh, options);
  double sum = 0;
  for (const Vec3& d : displacement) sum += d.squaredNorm();

  OpOutput out;
  out.positions = mesh.positions();
  out.stats.set("displacementRms", displacement.empty() ? 0.0 : std::sqrt(sum / displacement.size()));
  out.stats.set("averageEdgeLength", averageEdgeLength(context.session.build.mesh));
  return out;
}

}  // namespace geoshift::wasm

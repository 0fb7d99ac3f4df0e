// op "noise": seeded synthetic displacement for demos (same seed, same noise as `geoshift noise`).
#include <cmath>

#include "geoshift/geometry.hpp"
#include "geoshift/requests.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runNoise(const OpContext& context) {
  const NoiseOptions options = noiseOptions(context.params);
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

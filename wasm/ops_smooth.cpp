// op "smooth": Taubin λ|μ smoothing of the positions, as `geoshift smooth`.
#include "geoshift/requests.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runSmooth(const OpContext& context) {
  TaubinOptions options = smoothOptions(context.params);
  options.parallel.threads = context.threads(options.parallel.threads);
  Mesh mesh = context.session.build.mesh;
  taubinSmooth(mesh, options, context.progress);
  OpOutput out;
  out.positions = mesh.positions();
  out.stats.set("iterations", options.iterations);
  out.stats.set("threads", options.parallel.threads);
  return out;
}

}  // namespace geoshift::wasm

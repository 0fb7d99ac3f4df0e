// op "curvature": discrete curvature as the scalar "_CURVATURE" plus its color map, as
// `geoshift curvature` writes them (_CURVATURE and COLOR_0).
#include "geoshift/requests.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runCurvature(const OpContext& context) {
  const std::string kind = context.params.text("kind");
  const CurvatureKind k = curvatureKind(context.params);
  context.progress.step(0, "curvature");
  std::vector<double> values = curvatures(context.session.build.mesh).get(k);
  OpOutput out;
  // The CLI maps colors over the caller's vertices (its percentiles count every copy of a welded
  // vertex); mapping in the caller layout here keeps both outputs identical.
  const std::vector<int>& vertexOf = context.session.build.vertexOf;
  const std::vector<double> rgb = colorMap(toCallerLayout(values, 1, vertexOf));
  std::vector<double> meshRgb(3 * values.size(), 0.0);
  for (std::size_t i = 0; i < vertexOf.size(); ++i) {
    for (int c = 0; c < 3; ++c) meshRgb[3 * vertexOf[i] + c] = rgb[3 * i + c];
  }
  out.colors = std::move(meshRgb);
  out.scalars.emplace_back("_CURVATURE", std::move(values));
  out.stats.set("kind", kind);
  return out;
}

}  // namespace geoshift::wasm

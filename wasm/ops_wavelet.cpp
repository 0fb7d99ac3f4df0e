// op "wavelet": multiresolution smoothing (alpha < 1) or enhancement (alpha > 1) of the positions
// and, unless positionsOnly, the colors, as `geoshift wavelet` does it: lifting analysis to `levels`
// levels and synthesis with the detail gains alpha (docs/algorithms.md#wavelets).
#include <algorithm>

#include "geoshift/requests.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runWavelet(const OpContext& context) {
  const Session& s = context.session;
  const WaveletRequest request = waveletRequest(context.params);
  const Attribute* color = request.positionsOnly ? nullptr : s.attributes.find("color");
  AttributeSet signals(s.build.mesh.vertexCount());
  if (color) signals.set("color", 3, AttributeKind::Euclidean, color->values);

  const SynthesisResult r = waveletFilter(s.build.mesh, signals, request.options, request.alpha, context.progress);
  OpOutput out;
  out.positions = r.mesh.positions();
  if (color) {
    // Stored colors are in [0, 1]; enhancement can overshoot (clamped as the CLI does).
    std::vector<double> rgb = r.attributes.get("color").values;
    for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
    out.colors = std::move(rgb);
    out.colorsAreSignal = true;
  }
  out.stats.set("levels", request.options.levels);
  return out;
}

}  // namespace geoshift::wasm

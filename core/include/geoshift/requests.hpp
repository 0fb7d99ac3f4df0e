#pragma once
// What a request of the smaller ops means (noise, smooth, curvature, wavelet), for the wasm ops and
// the CLI commands of the same names: a request checked against the op's table (params.hpp) as the
// options of its core call. Filter and denoise requests have their own headers
// (filter_request.hpp, denoise_request.hpp).
#include <vector>

#include "geoshift/curvature.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/params.hpp"
#include "geoshift/smoothing.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift {

NoiseOptions noiseOptions(const ParamRequest& request);
TaubinOptions smoothOptions(const ParamRequest& request);
CurvatureKind curvatureKind(const ParamRequest& request);

struct WaveletRequest {
  WaveletOptions options;     // its levels
  std::vector<double> alpha;  // one gain for every level, or one per level
  bool positionsOnly = false; // leave colors as they are
};
WaveletRequest waveletRequest(const ParamRequest& request);

}  // namespace geoshift

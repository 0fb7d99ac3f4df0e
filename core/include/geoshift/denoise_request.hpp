#pragma once
// What a denoise request means, for every front end (the CLI's `denoise`, the wasm op `denoise`,
// Python's geoshift.denoise): the method, the mean shift preset and the optional parameters of the
// table paramSpecsOf("denoise") (params.hpp), turned into the options of the method's core call.
// Parameters of another method or preset are refused, not ignored (docs/architecture.md#parameters).
#include "geoshift/bilateral_normal.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/params.hpp"
#include "geoshift/smoothing.hpp"

namespace geoshift {

enum class DenoiseMethod {
  MeanShift,  // denoise() with DenoiseOptions (its preset: the default pipeline or the paper's)
  Bilateral,  // bilateralNormalDenoise()
  Taubin,     // taubinSmooth(), a baseline
};

struct DenoiseSettings {
  DenoiseMethod method = DenoiseMethod::MeanShift;
  DenoiseOptions meanShift;
  BilateralNormalOptions bilateral;
  TaubinOptions taubin;
};

// "meanshift", "bilateral", "taubin": the request's spelling.
const char* denoiseMethodName(DenoiseMethod method);

// The request over `base`: the method and the preset are the request's (given or default); every
// other parameter changes `base` only when given, so with base {} the defaults are the options
// structs' own, which the table shows.
DenoiseSettings denoiseSettings(const ParamRequest& request, DenoiseSettings base = {});
// The same from the values as a front end received them; throws InputError as ParamRequest does.
DenoiseSettings denoiseSettings(ParamValues given, DenoiseSettings base = {});

}  // namespace geoshift

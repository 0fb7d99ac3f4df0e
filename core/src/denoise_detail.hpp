#pragma once
// The two denoising pipelines behind denoise() (denoise.hpp), on the mesh as given (no hybrid).
#include "geoshift/denoise.hpp"

namespace geoshift::denoise_detail {

DenoiseResult denoiseDefault(Mesh& mesh, const DenoiseOptions& options, const Progress& progress);
DenoiseResult denoisePaper(Mesh& mesh, const DenoiseOptions& options, const Progress& progress);

}  // namespace geoshift::denoise_detail

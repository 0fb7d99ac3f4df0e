#pragma once
// The two denoising pipelines behind denoise() (denoise.hpp), on the mesh as given (no hybrid).
#include "geoshift/denoise.hpp"

namespace geoshift::denoise_detail {

DenoiseResult denoiseDefault(Mesh& mesh, const DenoiseOptions& options, const Progress& progress);
DenoiseResult denoisePaper(Mesh& mesh, const DenoiseOptions& options, const Progress& progress);

// Impulsive noise (docs/denoising.md#impulsive-noise): from the input y and its smoothed copy x,
// every vertex with a normal in `normals` gets the weight w = max(0, 1 − τ²/d²) of its displacement d
// = (x − y)·N (a non-negative garrote: near 1 for an outlier the smoothing pulled back, 0 for a
// vertex it moved less than τ) and ends at y + w (x + b − y), where b is the mean of y − x over its
// neighbours weighted by 1 − w: the detail the smoothing took from the neighbours, read where the
// input can be trusted and given back to the outlier. Vertices with w = 0 keep the input's
// position; those without a normal keep x.
void correctOutliers(const Mesh& mesh, const std::vector<Vec3>& input, std::vector<Vec3>& x,
                     const std::vector<Vec3>& normals, double tau);

// The weight w of candidate O in (1 − w) x_W + w x_O where the blend's risk, (1 − w) R_W + w R_O −
// w (1 − w) D, is least: 0.5 (1 − gap / (spread D)), gap = R_O − R_W, clamped to [0, 1]; 0 where D
// is not positive (docs/denoising.md#the-blend-of-least-risk). `spread` scales D (1: the optimum).
double blendWeight(double gap, double difference, double spread);

}  // namespace geoshift::denoise_detail

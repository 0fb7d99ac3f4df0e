#pragma once
// Taubin λ|μ smoothing (Taubin 1995; docs/algorithms.md#taubin-smoothing).
#include "geoshift/mesh.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

enum class LaplacianWeights { Uniform, Fujiwara, Cotangent };

struct TaubinOptions {
  int iterations = 10;      // each one a λ step and a μ step
  double lambda = 0.5;      // MeshLab's defaults
  double mu = -0.53;
  LaplacianWeights weights = LaplacianWeights::Uniform;
  ParallelOptions parallel;  // threads of the per-vertex loop; results do not depend on them
};

// Smooths positions in place. Boundary vertices use the 1D Laplacian of their two boundary
// neighbours (as vcglib); isolated vertices do not move. Throws InputError on lambda <= 0,
// mu >= -lambda or iterations < 0.
void taubinSmooth(Mesh& mesh, const TaubinOptions& options = {}, const Progress& progress = {});

}  // namespace geoshift

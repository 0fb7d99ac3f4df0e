#pragma once
// Seeded synthetic noise for demos and the denoising benchmark (docs/algorithms.md#noise-and-error-metrics).
// Uses its own generators (no std::*_distribution), so the same seed gives the same noise natively
// and in wasm.
#include <cstdint>
#include <vector>

#include "geoshift/mesh.hpp"

namespace geoshift {

enum class NoiseDistribution {
  Fixed,     // magnitude exactly amount * AEL
  Uniform,   // magnitude uniform in [0, amount * AEL]
  Gaussian,  // signed magnitude N(0, (amount * AEL)^2)
};
enum class NoiseDirection { Random, Normal };

struct NoiseOptions {
  double amount = 0.5;  // in multiples of the average edge length
  NoiseDistribution distribution = NoiseDistribution::Fixed;
  NoiseDirection direction = NoiseDirection::Random;
  std::uint64_t seed = 1;
};

// Displaces every non-isolated vertex in place; returns the displacement per vertex.
std::vector<Vec3> addNoise(Mesh& mesh, const NoiseOptions& options = {});

}  // namespace geoshift

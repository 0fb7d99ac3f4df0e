#pragma once
// Seeded synthetic noise for demos and the denoising benchmark (docs/algorithms.md#noise-and-error-metrics).
// Uses its own generators (no std::*_distribution), so the same seed gives the same noise natively
// and in wasm.
#include <cstdint>
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/parallel.hpp"

namespace geoshift {

enum class NoiseDistribution {
  Fixed,     // magnitude exactly amount * AEL
  Uniform,   // magnitude uniform in [0, amount * AEL]
  Gaussian,  // signed magnitude N(0, (amount * AEL)^2)
  Impulsive, // a fraction `impulseFraction` of the vertices, each N(0, (amount * AEL)^2); the rest stay
};
// Normal: along the vertex normal, with a random sign for Fixed and Uniform magnitudes (an unsigned
// magnitude would only inflate the mesh).
enum class NoiseDirection { Random, Normal };

struct NoiseOptions {
  double amount = 0.5;  // in multiples of the average edge length
  NoiseDistribution distribution = NoiseDistribution::Fixed;
  NoiseDirection direction = NoiseDirection::Random;
  std::uint64_t seed = 1;
  double impulseFraction = 0.1;  // Impulsive: the share of vertices moved, in (0, 1]
};

// Displaces every non-isolated vertex in place; returns the displacement per vertex.
std::vector<Vec3> addNoise(Mesh& mesh, const NoiseOptions& options = {});

}  // namespace geoshift

namespace geoshift {

// How noisy a mesh is, estimated from the mesh alone (docs/denoising.md#noise-estimate): at sampled
// vertices a quadric height field is fitted to the two-ring in the frame of its best-fit plane, and
// the residuals, corrected for the fit's own degrees of freedom, give the spread of positions across
// the surface. Creases and corners, which a quadric cannot follow, are left out by averaging the
// lower half of the per-vertex estimates (with the factor that makes that unbiased for Gaussian noise).
struct NoiseEstimate {
  double level = 0;    // RMS displacement across the surface, in multiples of the average edge length
  double absolute = 0; // the same in the mesh's units
  int samples = 0;     // vertices that contributed (interior, two-ring of at least 9 vertices)
  // The mean of all the per-vertex estimates, creases and corners included: at or above the noise
  // on most meshes (creases add to it), and above `level` where the noise is impulsive (a few
  // vertices moved far), which the lower half leaves out. In average edge lengths.
  double upperLevel = 0;
};

// Deterministic and independent of threads. Uses at most `maxSamples` vertices spread evenly over
// the index range. A mesh with no usable vertex gives level 0 and samples 0.
NoiseEstimate estimateNoise(const Mesh& mesh, int maxSamples = 40000);

// The noise level read from the mesh's highest frequencies (docs/denoising.md#noise-estimate): the
// uniform Laplacian applied twice to the positions, along the vertex normals of a copy smoothed by
// 10 Taubin steps, against the same operator's response to white noise (measured with 8 seeded ±1
// probes), over the vertices at least three rings from a crease (faces of that copy more than 30°
// apart) or a boundary. A plain mean, so it holds for any distribution of the noise; detail leaks in
// only as far as it reaches the top of the spectrum. In average edge lengths; 0 where every vertex is
// near a crease or a boundary. Deterministic and independent of `parallel`'s threads.
struct HighFrequencyNoise {
  double level = 0;
  // The kurtosis of that response over the same vertices, E d⁴ / (E d²)²: about 3 for Gaussian noise
  // along the normals, up to 4.7 in random directions (along N a Gaussian times a uniform cosine),
  // less for bounded noise (2.1–3.3 on the evaluation's fixed and uniform magnitudes), far above for
  // impulsive noise, a few vertices moved far (6.4–45); 0 where the level is
  // (docs/denoising.md#impulsive-noise).
  double kurtosis = 0;
  int samples = 0;  // the vertices read: those three rings from any crease, boundary or isolated vertex
};
HighFrequencyNoise highFrequencyNoise(const Mesh& mesh, const ParallelOptions& parallel = {});
double highFrequencyNoiseLevel(const Mesh& mesh, const ParallelOptions& parallel = {});  // its level

// Its parts: the sampled vertices (interior, not isolated, evenly spread over the index range), and
// the residual variance of the quadric fitted to each one's two-ring (−1 where unusable).
std::vector<int> noiseSampleVertices(const Mesh& mesh, int maxSamples = 40000);
std::vector<double> quadricResidualVariances(const Mesh& mesh, const std::vector<int>& vertices);

// The noise level read against the mesh's own planes (docs/denoising.md#noise-estimate, "Planes
// left untouched"), for meshes of flat faces whose noise left most faces where they were (sparse,
// impulsive noise on a CAD part): a face is *confirmed* when a face across one of its edges lies in
// its plane (normals within 1°), which noise of any density breaks and which clean flat parts keep.
// Each vertex reads its distance to the nearest plane of a confirmed face of its two-ring that does
// not touch it; the level is the RMS of those distances over the vertices that have one. Where
// creases meet, a vertex moved along one plane stays in the other, so the reading there is a lower
// one. In average edge lengths; all 0 on a mesh without confirmed faces.
struct PlanarNoise {
  double level = 0;
  double confirmedShare = 0;  // confirmed faces over all faces
  int samples = 0;            // vertices read
};
PlanarNoise planarNoise(const Mesh& mesh);
// Its parts, for the mesh's connectivity at the given positions: each vertex's distance to the
// nearest plane of a confirmed face of its two-ring not touching it (−1 where there is none); if
// asked for, the confirmed faces' share, which faces are confirmed, and which vertices lie in the
// plane of the face across the edge opposite them in one of their faces (within the same 1°).
std::vector<double> planarResiduals(const Mesh& mesh, const std::vector<Vec3>& positions, double* confirmedShare = nullptr,
                                    std::vector<char>* confirmedFaces = nullptr, std::vector<char>* inPlane = nullptr);

}  // namespace geoshift

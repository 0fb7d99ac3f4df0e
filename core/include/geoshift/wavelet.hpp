#pragma once
// Graph-wavelet multiresolution by lifting (docs/algorithms.md#wavelets): LOCAAT-style predict/update steps,
// batched over an independent set of vertices removed by half-edge collapses, level after level.
//
//   Multiresolution mr = analyze(mesh, attributes);            // coarse mesh + details
//   ... filter mr.coarse / mr.coarseAttributes (e.g. mean shift on the coarse mesh) ...
//   SynthesisResult r = synthesize(mr, mr.coarse.positions(), filtered, alpha);
//
// Positions and every attribute channel are lifted with the same weights, so the update also keeps
// the area-weighted centroid; where the update of the positions would flip a face, the odd vertices
// next to it send their update to their other even neighbours (still a minimum-norm u that keeps
// Σ A f invariant). Boundary vertices: see WaveletOptions::boundaryAngle. The fine mesh comes back
// with the input's connectivity and vertex order exactly; α = 1 on every level reconstructs the input
// (to round-off), α = 0 drops the details, α > 1 enhances them.
#include <cstdint>
#include <span>
#include <vector>

#include "geoshift/attributes.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

// Which vertices a level removes first (the odd set is chosen greedily in ascending cost).
enum class WaveletCost {
  Integral,  // smallest integral A_v first (LOCAAT): removes where sampling is densest -> even coarse meshes
  Residual,  // smallest position prediction residual first: removes where the surface is flattest
};

// Prediction weights p_oe of an odd vertex from its even neighbours (they sum to 1).
enum class WaveletWeights {
  MeanValue,        // Floater's mean value coordinates on the 3D one-ring: positive, reproduce linear
                    // functions exactly on a flat star-shaped ring
  InverseDistance,  // 1 / |x_o - x_e|
  Uniform,          // 1 / valence
};

struct WaveletOptions {
  // Maximum number of levels; analysis stops earlier when a level can remove nothing.
  int levels = 2;
  WaveletCost cost = WaveletCost::Integral;
  WaveletWeights weights = WaveletWeights::MeanValue;
  // Boundary vertices may be removed along the boundary polyline (collapsing into a boundary
  // neighbour, predicted linearly from the two boundary neighbours) where the polyline turns by at
  // most this many degrees; corners stay. A negative value keeps the whole boundary at full
  // resolution (then a grid's boundary fringe never coarsens).
  double boundaryAngle = 30.0;
  // A collapse is refused when a face's normal would turn by more than this (degrees, < 90 so that
  // no face ever flips).
  double maxNormalChange = 75.0;
  // Keep every level's mesh (for inspection and tests; costs memory).
  bool keepLevelMeshes = false;
  // The candidate order of a piece of a larger mesh (a tile), so that inside it the piece removes
  // the vertices the whole's analysis removes (docs/tiles.md#the-wavelet-order). Candidates go in
  // blocks of consecutive whole indices, cost bands, then index: wholeIndex gives each vertex's index
  // in the whole mesh, increasing with its index here (empty: its own index); costBounds the whole's
  // band bounds of each level (its WaveletLevel::costBounds; empty, and levels past those given:
  // quantiles of this mesh's own costs).
  std::vector<std::int64_t> wholeIndex;
  std::vector<std::vector<double>> costBounds;
};

// One analysis step: the vertices it removed (ids of the input mesh), each with its collapse target,
// its prediction and update weights over its even neighbours, and its details.
struct WaveletLevel {
  int vertexCount = 0;        // live vertices before this level
  std::vector<int> odd;       // removed vertices, in removal order
  std::vector<int> target;    // the even neighbour each odd vertex was collapsed into
  std::vector<int> offset;    // odd i uses neighbour entries [offset[i], offset[i+1])
  std::vector<int> neighbor;  // even neighbours (input ids)
  std::vector<double> predict;  // p_oe, summing to 1 per odd vertex
  std::vector<double> update;   // u_eo (minimum-norm, Σ_e A'_e u_eo = A_o)
  std::vector<double> detail;   // odd.size() rows of Multiresolution::channelCount() values
  std::vector<double> costBounds;  // upper bounds of the cost bands its candidate order used
};

// A level's mesh as kept with WaveletOptions::keepLevelMeshes.
struct WaveletLevelMesh {
  Mesh mesh;                    // positions are the lifted (coarse) positions of that level
  std::vector<int> inputVertex; // mesh vertex -> input vertex
  std::vector<int> parentFace;  // face -> the face of the previous level it came from (empty at level 0)
};

struct Multiresolution {
  Mesh fine;                     // the input mesh
  std::vector<WaveletLevel> levels;  // levels[0] removes from the input mesh; levels.back() yields the coarse mesh
  int requestedLevels = 0;

  Mesh coarse;                   // a real mesh of the remaining vertices (filter it as any mesh)
  AttributeSet coarseAttributes; // the lifted attributes on it (UnitVector rows normalised)
  std::vector<int> coarseToFine; // coarse vertex -> input vertex (increasing)
  std::vector<double> coarseIntegrals;  // the lifted integrals A of the coarse vertices

  // Layout of the lifted channels: x, y, z, then each attribute's dims in order (values empty).
  std::vector<Attribute> layout;
  // For UnitVector attributes: the norm of each coarse row before normalisation (per layout entry,
  // coarse vertex); synthesis scales the given unit rows by it, so unfiltered input round-trips exactly.
  std::vector<std::vector<double>> coarseNorms;

  std::vector<WaveletLevelMesh> levelMeshes;  // levels + 1 entries when kept, else empty

  int levelCount() const { return static_cast<int>(levels.size()); }
  int channelCount() const;
  // Live vertex counts: input, then after each level.
  std::vector<int> vertexCounts() const;
};

// Lifting analysis of the mesh's positions and all `signals` (per mesh vertex).
// Preconditions: signals.vertexCount() == mesh.vertexCount() (an empty set is fine).
// Throws InputError when options.levels < 0, options.maxNormalChange is not in (0, 90), the signal
// count does not match (naming the attribute), a value is not finite (naming attribute and vertex), or
// wholeIndex / costBounds are malformed (wrong count, not increasing, not finite).
// Throws Cancelled through `progress`.
Multiresolution analyze(const Mesh& mesh, const AttributeSet& signals, const WaveletOptions& options = {},
                        const Progress& progress = {});

struct SynthesisResult {
  Mesh mesh;                // the input connectivity and vertex order, synthesised positions
  AttributeSet attributes;  // synthesised attributes (UnitVector rows re-normalised)
};

// Inverse transform with detail gain alpha[k] on the details of level k (0 = finest); one value
// applies to all levels. `coarsePositions` and `coarseAttributes` are per coarse vertex (e.g.
// mr.coarse.positions() and a filtered mr.coarseAttributes).
// Throws InputError when alpha has neither 1 nor levelCount() (or requestedLevels) entries, an alpha
// is not finite, the position count differs from the coarse vertex count, or an attribute of the
// analysis is missing or has another dim/count (naming it).
SynthesisResult synthesize(const Multiresolution& mr, const std::vector<Vec3>& coarsePositions,
                           const AttributeSet& coarseAttributes, std::span<const double> alpha,
                           const Progress& progress = {});

// Convenience: analyse, keep the coarse signals as they are, synthesise with alpha.
SynthesisResult waveletFilter(const Mesh& mesh, const AttributeSet& signals, const WaveletOptions& options,
                              std::span<const double> alpha, const Progress& progress = {});

}  // namespace geoshift

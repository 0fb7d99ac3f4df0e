#pragma once
// The denoising evaluation's cases (docs/denoising.md#the-evaluation): clean meshes grouped in
// families, the rule that splits the families into a tuning set and a validation set, the noise
// each mesh gets, and the ground-truth pairs.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/noise.hpp"

namespace geoshift::eval {

// Broad: tuning cases only, reported apart (docs/denoising.md#the-evaluation, "The broad tuning set").
// Holdout: held out from every choice, validation's included; reported apart, run only as a record
// (docs/denoising.md#the-evaluation, "The holdout set").
enum class Set { Tuning, Validation, Broad, Holdout };
const char* setName(Set s);

// A clean mesh. Meshes of one family (the same object at two resolutions, with and without holes)
// always fall in the same set.
struct MeshEntry {
  std::string name;      // as printed
  std::string family;    // the split's key
  std::string category;  // what kind of surface (the split is balanced within each)
  bool seen = false;     // played a part in choosing earlier defaults: tuning set, whatever the hash
  bool broad = false;    // of the broad tuning set: never validation
  std::function<Mesh()> load;  // the clean mesh, any scale
  bool holdout = false;  // of the holdout set: never tuning, never validation
};

// The noise of one synthetic case.
struct NoiseSpec {
  std::string label;  // e.g. "gaussian 0.3 AEL along normals"
  NoiseOptions options;
};

// A case: a clean mesh and a noisy copy on the same connectivity, both scaled to the unit cube.
struct Case {
  std::string mesh, noise, family, category;
  Set set = Set::Tuning;
  Mesh clean, noisy;
  std::string gcnResult;  // for the GCN-Denoiser pairs: its published result file, else empty
};

// FNV-1a, 64 bits, of the bytes of `s`: the split's hash (fixed by its definition, not by a library).
std::uint64_t fnv1a(const std::string& s);

// Every clean mesh of the catalogue; files missing under `data` are left out with a note on stderr.
std::vector<MeshEntry> cleanMeshes(const std::filesystem::path& data);

// The broad tuning set's meshes, read from `dir` (CGAL's demo meshes as scripts/eval-data.sh
// unpacks them); none when `dir` does not exist (a note on stderr says how to fetch them), and a
// note for each listed file that is missing.
std::vector<MeshEntry> broadMeshes(const std::filesystem::path& dir);

// The holdout set's meshes, read from the same folder as the broad set's (CGAL's small demo meshes):
// each twice, split in four and subdivided by Loop, until it has at least holdoutMinVertices
// vertices; none when `dir` does not exist, and a note for each listed file that is missing.
inline constexpr int holdoutMinVertices = 3000;
std::vector<MeshEntry> holdoutMeshes(const std::filesystem::path& dir);

// Every triangle split in four at its edges' midpoints (a midpoint shared by the edge's faces); the
// input's vertices keep their indices, the midpoints follow. The surface does not move: every new
// triangle lies in its parent's plane.
Mesh splitInFour(const Mesh& mesh);

// Loop's subdivision (Loop 1987; β = (5/8 − (3/8 + cos(2π/k)/4)²) / k at a vertex of k
// neighbours): the connectivity of splitInFour, the positions smoothed. On a boundary the curve
// rules (edge midpoints; a boundary vertex 3/4 itself and 1/8 each boundary neighbour); a vertex on
// more than one boundary loop stays where it is. Every new position is a convex combination of old
// ones, and the scheme commutes with affine maps.
Mesh loopSubdivide(const Mesh& mesh);

// The split, decided by names alone before any result was seen: families already used to choose
// earlier defaults go to tuning, the broad set's to broad; within each category the other
// families, ordered by fnv1a of the family name, alternate validation, tuning, validation, ...
std::vector<std::pair<std::string, Set>> splitFamilies(const std::vector<MeshEntry>& meshes);

// The synthetic noises of a mesh: the paper's two readings of 0.5 AEL in random directions (fixed
// and uniform magnitude), Gaussian and impulsive noise at a level and in a direction picked by the
// hash of the mesh's name and the kind. `seed`: the noise's realization (the scoreboard's is 1; the
// kinds, levels and directions do not depend on it).
std::vector<NoiseSpec> noisesFor(const std::string& meshName, std::uint64_t seed = 1);

struct Pair {
  std::string name, family, clean, noisy, gcnResult;
};
std::vector<Pair> groundTruthPairs();

// The noisy file of a pair on the clean file's connectivity (the pairs share face lists and vertex
// order), both under the clean mesh's unit-cube transform. False (and a note) when files are missing.
bool loadPair(const std::filesystem::path& data, const Pair& p, Case& c);

// Positions of `file` (same vertex order as the pair's clean file) under the case's transform, as
// loadPair maps the noisy file: for results published by other methods.
std::vector<Vec3> loadResultPositions(const std::filesystem::path& data, const Pair& p, const std::string& file);

}  // namespace geoshift::eval

// Procedural terrain for benchmarks and demos: fBm value noise on a grid, flat lakes, and
// vegetation patches. Only +, -, *, / and floor: no libm function and no std:: distribution
// differs between glibc (native) and musl (Emscripten), so both give bit-identical meshes.
#include <algorithm>
#include <climits>
#include <cmath>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/terrain.hpp"

namespace geoshift {
namespace {

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A value in [-1, 1) for a lattice point of one noise layer; rowKey = mix(iy + salt).
double latticeInRow(std::int64_t ix, std::uint64_t rowKey) {
  const std::uint64_t h = mix(static_cast<std::uint64_t>(ix) * 0x9e3779b97f4a7c15ull ^ rowKey);
  return static_cast<double>(h >> 11) * 0x1.0p-52 - 1.0;
}

double lattice(std::int64_t ix, std::int64_t iy, std::uint64_t salt) {
  return latticeInRow(ix, mix(static_cast<std::uint64_t>(iy) + salt));
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }  // C2 at the lattice

double valueNoise(double x, double y, std::uint64_t salt) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  const double u = fade(x - fx), v = fade(y - fy);
  const std::uint64_t row0 = mix(static_cast<std::uint64_t>(iy) + salt), row1 = mix(static_cast<std::uint64_t>(iy + 1) + salt);
  const double a = latticeInRow(ix, row0), b = latticeInRow(ix + 1, row0);
  const double c = latticeInRow(ix, row1), d = latticeInRow(ix + 1, row1);
  const double top = a + (b - a) * u, bottom = c + (d - c) * u;
  return top + (bottom - top) * v;
}

// Fractal Brownian motion normalised to about [-1, 1]. Octaves are shifted so that their lattices
// do not line up (which would show as a grid pattern).
double fbm(double x, double y, int octaves, double gain, std::uint64_t salt) {
  double sum = 0, amp = 1, norm = 0, freq = 1;
  for (int k = 0; k < octaves; ++k) {
    sum += amp * valueNoise(x * freq + 0.371 * k, y * freq - 0.613 * k, salt + 0x632be59bd9b4e019ull * (k + 1));
    norm += amp;
    amp *= gain;
    freq *= 2.0;
  }
  return sum / norm;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

TerrainMesh proceduralTerrain(const TerrainOptions& o, const Progress& progress) {
  if (o.size < 2) throw InputError("procedural terrain: size must be >= 2 (got " + std::to_string(o.size) + ")");
  if (static_cast<long long>(o.size - 1) * (o.size - 1) * 2 * 3 > INT_MAX)
    throw InputError("procedural terrain: size " + std::to_string(o.size) + " exceeds 32-bit indices");
  if (!(o.cellSize > 0) || !std::isfinite(o.cellSize)) throw InputError("procedural terrain: cellSize must be > 0");
  if (!(o.relief >= 0) || !std::isfinite(o.relief)) throw InputError("procedural terrain: relief must be >= 0");
  if (!(o.roughness > 0 && o.roughness < 1)) throw InputError("procedural terrain: roughness must be in (0, 1)");
  if (!(o.forestCover >= 0 && o.forestCover <= 1)) throw InputError("procedural terrain: forestCover must be in [0, 1]");
  if (!(o.waterLevel >= 0 && o.waterLevel < 1)) throw InputError("procedural terrain: waterLevel must be in [0, 1)");
  if (!(o.maxVegetationHeight >= 0) || !std::isfinite(o.maxVegetationHeight))
    throw InputError("procedural terrain: maxVegetationHeight must be >= 0");

  const int n = o.size;
  const double extent = o.cellSize * (n - 1);
  const double relief = o.relief > 0 ? o.relief : 0.15 * extent;
  // Base features span a quarter of the tile; octaves are added until they reach two cells, so a
  // larger size samples the same landscape with more detail.
  constexpr double kBase = 4.0;
  int octaves = 1;
  for (double f = kBase; f * 2.0 < 0.5 * (n - 1) && octaves < 24; f *= 2.0) ++octaves;
  const std::uint64_t seed = mix(o.seed ^ 0x5eedull);
  const std::uint64_t saltGround = mix(seed + 1), saltForest = mix(seed + 2), saltCanopy = mix(seed + 3);
  const std::uint64_t saltJitter = mix(seed + 4);

  TerrainMesh out;
  const size_t nv = static_cast<size_t>(n) * n;
  out.positions.resize(nv);
  std::vector<double> vegetation(nv), cls(nv);
  const double waterZ = relief * o.waterLevel;
  const double forestThreshold = 1.0 - 2.0 * o.forestCover;  // fbm is roughly symmetric in [-1, 1]
  const double inv = 1.0 / (n - 1);
  for (int row = 0; row < n; ++row) {
    if ((row & 63) == 0) progress.step(double(row) / n, "procedural terrain");
    const double v = row * inv;
    for (int col = 0; col < n; ++col) {
      const double u = col * inv;
      const size_t i = static_cast<size_t>(row) * n + col;
      const double g = 0.5 + 0.5 * fbm(kBase * u, kBase * v, octaves, o.roughness, saltGround);
      // Squaring flattens valleys and sharpens ridges, as in eroded relief.
      double z = relief * g * g * 1.6;
      const bool water = z <= waterZ;
      if (water) z = waterZ;
      out.positions[i] = Vec3(col * o.cellSize, row * o.cellSize, z);
      double veg = 0;
      if (!water) {
        const double forest = fbm(2.0 * u, 2.0 * v, 5, 0.5, saltForest);
        const double canopy = 0.5 + 0.5 * fbm(16.0 * u, 16.0 * v, 3, 0.5, saltCanopy);
        const double jitter = lattice(col, row, saltJitter);  // single crowns and gaps
        const double treeLine = 1.0 - smoothstep(0.55, 0.85, z / (relief * 1.6));
        const double cover = smoothstep(forestThreshold, forestThreshold + 0.15, forest) * treeLine;
        veg = o.maxVegetationHeight * cover * (0.3 + 0.7 * canopy) * (1.0 + 0.15 * jitter);
        veg += 0.4 * (0.5 + 0.5 * jitter) * (1.0 - cover);  // grass and shrubs between the trees
        veg = std::clamp(veg, 0.0, o.maxVegetationHeight);
      }
      vegetation[i] = veg;
      cls[i] = water ? 9 : veg < 0.2 ? 2 : veg < 2.0 ? 3 : veg < 5.0 ? 4 : 5;
    }
  }
  out.faces.reserve(2 * static_cast<size_t>(n - 1) * (n - 1));
  for (int row = 0; row + 1 < n; ++row) {
    for (int col = 0; col + 1 < n; ++col) {
      const int a = row * n + col, b = a + 1, c = a + n + 1, d = a + n;
      // Alternating diagonals: no preferred direction for the filters to pick up.
      if ((row + col) & 1) {
        out.faces.push_back({a, b, d});
        out.faces.push_back({b, c, d});
      } else {
        out.faces.push_back({a, b, c});
        out.faces.push_back({a, c, d});
      }
    }
  }
  out.attributes = AttributeSet(static_cast<int>(nv));
  out.attributes.set("_VEGETATION_HEIGHT", 1, AttributeKind::Euclidean, std::move(vegetation));
  out.attributes.set("_CLASS", 1, AttributeKind::Euclidean, std::move(cls));
  out.report.pointsRead = out.report.pointsUsed = static_cast<std::int64_t>(nv);
  out.report.notes.push_back("procedural terrain: seed " + std::to_string(o.seed) + ", " + std::to_string(octaves) +
                             " octaves, relief " + formatNumber(relief) + " m");
  return out;
}

}  // namespace geoshift

// Grid terrains: triangulated elevation rasters.
#include <climits>
#include <cmath>

#include "geoshift/error.hpp"
#include "geoshift/terrain.hpp"

namespace geoshift {
namespace {

std::string cellName(int col, int row) {
  return "cell (column " + std::to_string(col) + ", row " + std::to_string(row) + ")";
}

}  // namespace

TerrainMesh gridTerrain(const ElevationGrid& grid, const GridTerrainOptions& options, const Progress& progress) {
  const int w = grid.width, h = grid.height;
  if (w < 1 || h < 1) throw InputError("elevation grid: size " + std::to_string(w) + " x " + std::to_string(h));
  if (static_cast<long long>(w) * h > INT_MAX / 2)
    throw InputError("elevation grid: " + std::to_string(w) + " x " + std::to_string(h) + " cells is too large");
  if (grid.values.size() != static_cast<size_t>(w) * h)
    throw InputError("elevation grid: " + std::to_string(grid.values.size()) + " values for " + std::to_string(w) +
                     " x " + std::to_string(h) + " cells");
  const auto& t = grid.transform;
  double det = t[1] * t[5] - t[2] * t[4];
  for (double v : t)
    if (!std::isfinite(v)) det = 0;
  if (det == 0) throw InputError("elevation grid: the cell-to-coordinates transform is singular or not finite");

  TerrainMesh out;
  out.report.pointsRead = static_cast<std::int64_t>(w) * h;
  out.report.notes = grid.notes;
  std::vector<int> vertexOf(static_cast<size_t>(w) * h, -1);

  // Geographic rasters: metres on a local equirectangular projection about the raster centre.
  const bool toMeters = grid.geographic && options.geographicToMeters;
  const double lon0 = t[0] + 0.5 * w * t[1] + 0.5 * h * t[2], lat0 = t[3] + 0.5 * w * t[4] + 0.5 * h * t[5];
  constexpr double kEarthRadius = 6371008.8, kDeg = 3.14159265358979323846 / 180.0;
  const double mx = kEarthRadius * kDeg * std::cos(lat0 * kDeg), my = kEarthRadius * kDeg;
  if (toMeters)
    out.report.notes.push_back("geographic raster: x/y are metres east/north of lon " + std::to_string(lon0) +
                               ", lat " + std::to_string(lat0) + " (local equirectangular projection)");
  else if (grid.geographic)
    out.report.notes.push_back("geographic raster: x/y are degrees of longitude/latitude, z is in the raster's units");

  std::vector<double> elevation;
  for (int row = 0; row < h; ++row) {
    if ((row & 255) == 0) progress.step(0.5 * row / h, "grid vertices");
    for (int col = 0; col < w; ++col) {
      const double z = grid.values[static_cast<size_t>(row) * w + col];
      if (std::isnan(z)) {
        ++out.report.nodataCells;
        continue;
      }
      if (!std::isfinite(z)) throw InputError("elevation grid: " + cellName(col, row) + " is infinite");
      double x = t[0] + (col + 0.5) * t[1] + (row + 0.5) * t[2];
      double y = t[3] + (col + 0.5) * t[4] + (row + 0.5) * t[5];
      if (toMeters) x = (x - lon0) * mx, y = (y - lat0) * my;
      vertexOf[static_cast<size_t>(row) * w + col] = static_cast<int>(out.positions.size());
      out.positions.emplace_back(x, y, z);
      elevation.push_back(z);
    }
  }
  if (out.positions.empty()) throw InputError("elevation grid: every cell is nodata");

  // Column/row axes turn counter-clockwise in x/y when det > 0; otherwise (north-up rasters,
  // rows running south) every face is reversed so that all face +z.
  const bool flip = det < 0;
  auto emit = [&](int a, int b, int c) {
    out.faces.push_back(flip ? Face{a, c, b} : Face{a, b, c});
  };
  for (int row = 0; row + 1 < h; ++row) {
    if ((row & 255) == 0) progress.step(0.5 + 0.5 * row / h, "grid faces");
    for (int col = 0; col + 1 < w; ++col) {
      const size_t i = static_cast<size_t>(row) * w + col;
      // The quad's corners in counter-clockwise order of the column/row frame.
      const int q[4] = {vertexOf[i], vertexOf[i + 1], vertexOf[i + 1 + w], vertexOf[i + w]};
      const int valid = (q[0] >= 0) + (q[1] >= 0) + (q[2] >= 0) + (q[3] >= 0);
      if (valid == 4) {
        emit(q[0], q[1], q[2]);
        emit(q[0], q[2], q[3]);
      } else if (valid == 3) {
        int tri[3], k = 0;
        for (int v : q)
          if (v >= 0) tri[k++] = v;  // dropping one corner keeps the others' cyclic order
        emit(tri[0], tri[1], tri[2]);
      }
    }
  }
  out.report.pointsUsed = static_cast<std::int64_t>(out.positions.size());
  if (out.faces.empty()) throw InputError("elevation grid: no triangle (no 2 x 2 block with three or four valid cells)");
  out.attributes = AttributeSet(static_cast<int>(out.positions.size()));
  out.attributes.set("_ELEVATION", 1, AttributeKind::Euclidean, std::move(elevation));
  return out;
}

}  // namespace geoshift

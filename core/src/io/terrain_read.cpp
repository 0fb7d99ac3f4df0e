// Terrain files by extension.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geoshift/terrain.hpp"
#include "io_detail.hpp"

namespace geoshift {

TerrainMesh readTerrain(const std::string& path, const TerrainReadOptions& options, const Progress& progress) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  auto withPath = [&](auto&& build) {
    try {
      return build();
    } catch (const InputError& e) {
      const std::string msg = e.what();
      if (msg.rfind(path + ":", 0) == 0) throw;
      throw InputError(path + ": " + msg);
    }
  };
  if (ext == ".las" || ext == ".laz" || ext == ".ply") {
    TerrainPoints pts = ext == ".ply" ? readPlyPoints(path) : readLas(path);
    TerrainMesh m = withPath([&] { return pointTerrain(pts, options.points, progress); });
    m.report.notes.insert(m.report.notes.begin(), pts.notes.begin(), pts.notes.end());
    return m;
  }
  if (ext == ".tif" || ext == ".tiff") {
    const ElevationGrid g = readGeoTiff(path);
    return withPath([&] { return gridTerrain(g, options.grid, progress); });
  }
  io::fail(path, "not a terrain file: the extension must be .las, .laz, .ply, .tif or .tiff");
}

}  // namespace geoshift

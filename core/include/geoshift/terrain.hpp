#pragma once
// Terrain meshes: 2.5D Delaunay triangulation of point sets, grid triangulation of elevation
// rasters, height above ground, a procedural fractal terrain, and (native only, geoshift_io) the
// readers for LAS, PLY point sets and DEM GeoTIFFs.
//
// Terrain meshes are z-up, faces counter-clockwise seen from above (+z). Per-vertex attributes use
// the glTF custom-attribute names they are written under: _ELEVATION, _HEIGHT_ABOVE_GROUND,
// _CLASS (ASPRS LAS codes: 2 ground, 3/4/5 low/medium/high vegetation, 9 water, ...),
// _VEGETATION_HEIGHT, and COLOR_0 (dim 3, RGB in [0, 1]).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geoshift/attributes.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

// --- 2.5D Delaunay triangulation -------------------------------------------------------------

enum class InsertionOrder {
  Sweep,    // radial sweep from the centre (fast, O(n log n) in practice); the default
  AsGiven,  // input order, each point located by walking (slow; exercises the interior-insertion path)
};

struct DelaunayOptions {
  InsertionOrder order = InsertionOrder::Sweep;
};

struct Delaunay2D {
  // Triangles over the input point indices, counter-clockwise. Only kept points are referenced.
  std::vector<Face> faces;
  // 3 per face: the half-edge (3f + k, from corner k to corner k+1) on the other side, -1 on the hull.
  std::vector<int> twins;
  // Input point -> the point kept in its place: itself, or the first earlier point with the same
  // (snapped) xy. Duplicates are not triangulated.
  std::vector<int> keptAs;
  int duplicates = 0;
  // The convex hull, counter-clockwise, as kept point indices.
  std::vector<int> hull;
};

// Delaunay triangulation of the xy of `points` (z ignored). The predicates are exact on
// coordinates rounded to a 2^28 grid over the bounding box, so points closer than 2^-28 of the
// extent count as duplicates; the result is then exactly Delaunay for the rounded points
// (cocircular ties broken arbitrarily) and covers their convex hull.
// Throws InputError when a coordinate is NaN/Inf (naming the point) or when fewer than three
// distinct points or only collinear ones are given. Cancellable through `progress`.
Delaunay2D delaunay2d(const std::vector<Vec3>& points, const DelaunayOptions& options = {},
                      const Progress& progress = {});

// --- terrain meshes --------------------------------------------------------------------------

struct TerrainReport {
  std::int64_t pointsRead = 0;       // points or raster cells in the input
  std::int64_t pointsUsed = 0;       // vertices of the mesh
  std::int64_t duplicatesDropped = 0;
  std::int64_t nodataCells = 0;
  std::int64_t groundPoints = 0;     // points of the ground class (point sets)
  std::vector<std::string> notes;    // what was assumed or converted, for the user
};

struct TerrainMesh {
  std::vector<Vec3> positions;
  std::vector<Face> faces;
  AttributeSet attributes;  // over positions
  TerrainReport report;

  TriangleSoup soup() const { return {positions, faces}; }
};

// A point cloud as read from a file. classes and colors are empty or one per point.
struct TerrainPoints {
  std::vector<Vec3> positions;
  std::vector<int> classes;
  std::vector<Eigen::Vector3d> colors;  // RGB in [0, 1]
  std::vector<std::string> notes;       // reader remarks (color scaling, skipped records, ...)
};

struct PointTerrainOptions {
  bool groundOnly = false;  // triangulate only the ground points
  int groundClass = 2;      // ASPRS ground; CGAL's b9 training labels use 0
};

// Height of each of `points` above the ground surface: z minus the z of the Delaunay TIN of
// `ground` at the point's xy (linear inside the TIN; outside its hull, linear along the nearest
// hull edge). Throws InputError as delaunay2d does for `ground`, or when a point is NaN/Inf.
std::vector<double> heightAboveGround(const std::vector<Vec3>& ground, const std::vector<Vec3>& points,
                                      const Progress& progress = {});

// 2.5D Delaunay terrain of a point cloud (all points, or only the ground class). Attributes:
// _HEIGHT_ABOVE_GROUND (against the TIN of the ground class; with fewer than three ground points,
// z minus the minimum z, which a report note says), _CLASS when classes are given, COLOR_0 when
// colors are given. xy duplicates keep the first point.
// Throws InputError when classes/colors do not match the points, on NaN/Inf, and when fewer than
// three non-collinear points are selected (naming the selection).
TerrainMesh pointTerrain(const TerrainPoints& points, const PointTerrainOptions& options = {},
                         const Progress& progress = {});

// An elevation raster. values row-major, row 0 first; NaN = nodata.
struct ElevationGrid {
  int width = 0;
  int height = 0;
  std::vector<double> values;
  // Cell (col, row) has its centre at x = t[0] + (col+0.5) t[1] + (row+0.5) t[2],
  // y = t[3] + (col+0.5) t[4] + (row+0.5) t[5] (GDAL's geotransform).
  std::array<double, 6> transform{0, 1, 0, 0, 0, -1};
  bool geographic = false;  // x/y are longitude/latitude in degrees
  std::vector<std::string> notes;
};

struct GridTerrainOptions {
  // Geographic rasters: x/y become metres east/north of the raster centre (equirectangular on
  // the mean Earth radius; fine for tiles of a few degrees). Off: degrees as they are.
  bool geographicToMeters = true;
};

// One vertex per valid cell (at its centre, z = value) and two triangles per quad of valid cells;
// a quad with one nodata corner gives the triangle of the other three. Attribute _ELEVATION.
// Throws InputError when the sizes do not match, a value is Inf, the transform is singular, or
// no cell is valid.
TerrainMesh gridTerrain(const ElevationGrid& grid, const GridTerrainOptions& options = {},
                        const Progress& progress = {});

struct TerrainOptions {
  int size = 257;             // vertices per side (size x size)
  std::uint64_t seed = 1;
  double cellSize = 1.0;      // metres between grid vertices
  double relief = 0.0;        // elevation range scale in metres; 0: 15% of the extent
  double roughness = 0.5;     // amplitude ratio between octaves (0.3 smooth .. 0.7 rugged)
  double forestCover = 0.45;  // fraction of land covered by vegetation patches
  double maxVegetationHeight = 30.0;
  double waterLevel = 0.12;   // fraction of the elevation range flooded (class 9)
};

// A size x size grid over [0, (size-1) cellSize]^2 with a fractal (fBm value-noise) heightfield
// and attributes _VEGETATION_HEIGHT (0..maxVegetationHeight) and _CLASS (2 ground, 3 low,
// 4 medium, 5 high vegetation, 9 water). Deterministic: the same options give bit-identical
// output natively and in wasm (own hash, no libm calls); the landscape does not depend on size.
// Throws InputError when size < 2, the mesh would exceed 2^31 indices, or an option is out of range.
TerrainMesh proceduralTerrain(const TerrainOptions& options = {}, const Progress& progress = {});

// --- readers (geoshift_io, native only) --------------------------------------------------------
// All throw InputError naming the file and what is wrong (truncated, unsupported variant, ...).

// LAS 1.0-1.4, point formats 0-10: positions (scaled), classification, RGB when the format has
// it (16-bit; files whose colors all fit in 8 bits are read as 8-bit, as many writers store them).
// LAZ (compressed) is refused with a message: no LASzip library is packaged in Debian 12.
TerrainPoints readLas(const std::string& path);
// PLY (ascii / binary) vertex element: x y z, optional red green blue, optional class,
// classification or label (int). Faces, if any, are ignored.
TerrainPoints readPlyPoints(const std::string& path);
// Single-image GeoTIFF (strips or tiles, any libtiff compression, int/uint/float samples, band 1):
// ModelPixelScale + ModelTiepoint or ModelTransformation, GDAL_NODATA, geographic model type.
// Without georeferencing, cells are 1 unit apart (with a note).
ElevationGrid readGeoTiff(const std::string& path);

struct TerrainReadOptions {
  PointTerrainOptions points;
  GridTerrainOptions grid;
};
// By extension: .las .laz .ply -> pointTerrain, .tif .tiff -> gridTerrain.
TerrainMesh readTerrain(const std::string& path, const TerrainReadOptions& options = {},
                        const Progress& progress = {});

}  // namespace geoshift

// Terrain readers: LAS, PLY point sets and DEM GeoTIFFs, on the samples of ../shared/data and on
// small files written here. Expected numbers and where they come from are next to each check.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "geoshift/error.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/terrain.hpp"
#include "support.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

struct Range {
  double lo = INFINITY, hi = -INFINITY;
};

Range range(const std::vector<double>& v, int dim = 1, int c = 0) {
  Range r;
  for (size_t i = c; i < v.size(); i += dim) r.lo = std::min(r.lo, v[i]), r.hi = std::max(r.hi, v[i]);
  return r;
}

Range axis(const std::vector<Vec3>& p, int k) {
  Range r;
  for (const Vec3& q : p) r.lo = std::min(r.lo, q[k]), r.hi = std::max(r.hi, q[k]);
  return r;
}

std::map<int, int> histogram(const std::vector<int>& v) {
  std::map<int, int> h;
  for (int c : v) ++h[c];
  return h;
}

template <class T>
void put(std::string& b, size_t at, T v) {
  std::memcpy(&b[at], &v, sizeof v);
}

struct LasPoint {
  std::int32_t x, y, z;
  std::uint8_t classByte;
  std::uint16_t r, g, b;
};

// A LAS file with no VLR, scale 0.01, offset (1000, 2000, 0).
std::string lasBytes(int minor, int format, const std::vector<LasPoint>& pts) {
  const size_t header = minor >= 4 ? 375 : (minor == 3 ? 235 : 227);
  const size_t rec = format == 7 ? 36 : (format == 3 ? 34 : 20);
  std::string b(header + rec * pts.size(), '\0');
  std::memcpy(&b[0], "LASF", 4);
  b[24] = 1, b[25] = static_cast<char>(minor);
  put<std::uint16_t>(b, 94, static_cast<std::uint16_t>(header));
  put<std::uint32_t>(b, 96, static_cast<std::uint32_t>(header));
  b[104] = static_cast<char>(format);
  put<std::uint16_t>(b, 105, static_cast<std::uint16_t>(rec));
  put<std::uint32_t>(b, 107, format >= 6 ? 0u : static_cast<std::uint32_t>(pts.size()));
  for (int k = 0; k < 3; ++k) put<double>(b, 131 + 8 * k, 0.01);
  put<double>(b, 155, 1000.0), put<double>(b, 163, 2000.0), put<double>(b, 171, 0.0);
  if (minor >= 4) put<std::uint64_t>(b, 247, pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    const size_t at = header + i * rec;
    put(b, at, pts[i].x), put(b, at + 4, pts[i].y), put(b, at + 8, pts[i].z);
    if (format == 7) {
      b[at + 16] = static_cast<char>(pts[i].classByte);
      put(b, at + 30, pts[i].r), put(b, at + 32, pts[i].g), put(b, at + 34, pts[i].b);
    } else {
      b[at + 15] = static_cast<char>(pts[i].classByte);
      if (format == 3) put(b, at + 28, pts[i].r), put(b, at + 30, pts[i].g), put(b, at + 32, pts[i].b);
    }
  }
  return b;
}

std::vector<LasPoint> fourPoints(std::uint8_t c0, std::uint8_t c1) {
  return {{0, 0, 100, c0, 0, 0, 0}, {1000, 0, 200, c1, 65535, 0, 0},
          {0, 1000, 300, c0, 0, 65535, 0}, {1000, 1000, 400, c1, 0, 0, 32768}};
}

}  // namespace

TEST_CASE("LAS samples: point counts, classes, ranges and colors", "[terrain][las][data]") {
  const auto simple = sharedData("pdal_testdata/las/simple.las");
  GEOSHIFT_SKIP_IF_MISSING(simple, "pdal_testdata/las/simple.las");
  // From the LAS header (count, min/max at bytes 107 and 179-226, read with Python's struct) and
  // a pass over the records for classes and RGB (also in data/README.md: classes 1:789, 2:276).
  const TerrainPoints s = readLas(simple->string());
  CHECK(s.positions.size() == 1065u);
  CHECK(histogram(s.classes) == std::map<int, int>{{1, 789}, {2, 276}});
  CHECK(axis(s.positions, 0).lo == Approx(635619.85));
  CHECK(axis(s.positions, 0).hi == Approx(638982.55));
  CHECK(axis(s.positions, 1).lo == Approx(848899.70));
  CHECK(axis(s.positions, 1).hi == Approx(853535.43));
  CHECK(axis(s.positions, 2).lo == Approx(406.59));
  CHECK(axis(s.positions, 2).hi == Approx(586.38));
  // Colors are stored as 8-bit values (max 249/239/249) in the 16-bit fields.
  REQUIRE(s.colors.size() == 1065u);
  double maxRed = 0;
  for (const auto& c : s.colors) maxRed = std::max(maxRed, c.x());
  CHECK(maxRed == Approx(249.0 / 255.0));

  const TerrainMesh m = readTerrain(simple->string());
  CHECK(m.positions.size() == 1065u);  // no xy duplicates (Python: set of raw (X, Y))
  CHECK(buildMesh(m.soup()).report.clean());
  const auto& cls = m.attributes.get("_CLASS").values;
  const auto& hag = m.attributes.get("_HEIGHT_ABOVE_GROUND").values;
  for (size_t v = 0; v < cls.size(); ++v)
    if (cls[v] == 2) CHECK(hag[v] == 0.0);  // ground points are vertices of the ground TIN
  CHECK(range(m.attributes.get("COLOR_0").values, 3, 0).hi == Approx(249.0 / 255.0));
}

TEST_CASE("autzen LAS loads: all points and ground only", "[terrain][las][data]") {
  const auto autzen = sharedData("pdal_testdata/las/autzen_trim.las");
  GEOSHIFT_SKIP_IF_MISSING(autzen, "pdal_testdata/las/autzen_trim.las");
  // Header: 110000 points, x 636001.76..637179.22, y 848935.20..849497.90, z 406.26..520.51;
  // classes 1:83893, 2:26107 (data/README.md); 109993 distinct raw (X, Y) pairs, 26107 among the
  // ground points (Python over the records).
  const TerrainMesh m = readTerrain(autzen->string());
  CHECK(m.report.pointsRead == 110000);
  CHECK(m.report.groundPoints == 26107);
  CHECK(m.positions.size() == 109993u);
  CHECK(m.report.duplicatesDropped == 7);
  CHECK(axis(m.positions, 0).lo == Approx(636001.76));
  CHECK(axis(m.positions, 0).hi == Approx(637179.22));
  CHECK(axis(m.positions, 1).lo == Approx(848935.20));
  CHECK(axis(m.positions, 1).hi == Approx(849497.90));
  CHECK(axis(m.positions, 2).lo == Approx(406.26));
  CHECK(axis(m.positions, 2).hi == Approx(520.51));
  CHECK(range(m.attributes.get("_CLASS").values).lo == 1);
  CHECK(range(m.attributes.get("_CLASS").values).hi == 2);
  const Range h = range(m.attributes.get("_HEIGHT_ABOVE_GROUND").values);
  CHECK(h.hi > 10.0);  // trees and buildings
  CHECK(h.hi <= 520.51 - 406.26);
  const MeshBuild b = buildMesh(m.soup());
  CHECK(b.report.clean());
  CHECK(b.mesh.boundaryLoops().size() == 1u);

  TerrainReadOptions ground;
  ground.points.groundOnly = true;
  const TerrainMesh g = readTerrain(autzen->string(), ground);
  CHECK(g.positions.size() == 26107u);
  CHECK(range(g.attributes.get("_CLASS").values).lo == 2);
  CHECK(range(g.attributes.get("_HEIGHT_ABOVE_GROUND").values).hi == 0.0);
}

TEST_CASE("CGAL b9 PLY point set with labels and colors", "[terrain][ply][data]") {
  const auto b9 = sharedData("cgal_debian_libcgal_demo/data/points_3/b9_training.ply");
  GEOSHIFT_SKIP_IF_MISSING(b9, "cgal_debian_libcgal_demo/data/points_3/b9_training.ply");
  // Header: 22300 vertices (double x y z, uchar rgb, int label). From the records (Python):
  // labels -1:19853, 0:1567, 1:314, 2:566; 22299 distinct (x, y); x 596648.0625..596738.9375,
  // z 73.50153..97.18581; RGB 0..255.
  const TerrainPoints p = readPlyPoints(b9->string());
  CHECK(p.positions.size() == 22300u);
  CHECK(histogram(p.classes) == std::map<int, int>{{-1, 19853}, {0, 1567}, {1, 314}, {2, 566}});
  CHECK(axis(p.positions, 0).lo == 596648.0625);
  CHECK(axis(p.positions, 0).hi == 596738.9375);
  CHECK(axis(p.positions, 2).lo == Approx(73.50153350830078));
  CHECK(axis(p.positions, 2).hi == Approx(97.18580627441406));
  TerrainReadOptions o;
  o.points.groundClass = 0;  // CGAL's training labels: 0 = ground
  const TerrainMesh m = readTerrain(b9->string(), o);
  CHECK(m.positions.size() == 22299u);
  CHECK(m.report.groundPoints == 1567);
  CHECK(range(m.attributes.get("COLOR_0").values, 3, 0).lo == 0.0);
  CHECK(range(m.attributes.get("COLOR_0").values, 3, 0).hi <= 1.0);
  const auto& cls = m.attributes.get("_CLASS").values;
  const auto& hag = m.attributes.get("_HEIGHT_ABOVE_GROUND").values;
  double roof = 0;
  for (size_t v = 0; v < cls.size(); ++v) {
    if (cls[v] == 0) CHECK(hag[v] == 0.0);
    if (cls[v] == 2) roof = std::max(roof, hag[v]);
  }
  CHECK(roof > 3.0);  // roofs stand above the ground
}

TEST_CASE("DEM GeoTIFF samples: grid counts, nodata, georeferencing, elevation range", "[terrain][geotiff][data]") {
  const auto elev = sharedData("dem_debian_r_packages/terra/elev.tif");
  GEOSHIFT_SKIP_IF_MISSING(elev, "dem_debian_r_packages/terra/elev.tif");
  // Tags (tifffile): 95 x 90 int16, LZW, GDAL_NODATA -32768, pixel scale 0.008333 deg, tie point
  // (0, 0) -> (5.741667, 50.191667), geographic, PixelIsArea. Pixel counts (tifffile after
  // tiffcp -c none): 4608 valid cells, 4382 quads of 4 valid and 138 of 3 -> 8902 triangles;
  // elevation 141..547 (data/README.md: 141..547 m).
  const ElevationGrid g = readGeoTiff(elev->string());
  CHECK(g.width == 95);
  CHECK(g.height == 90);
  CHECK(g.geographic);
  CHECK(g.transform[1] == Approx(0.008333333333333337));
  CHECK(g.transform[3] == Approx(50.19166666666666));
  TerrainReadOptions degrees;
  degrees.grid.geographicToMeters = false;
  const TerrainMesh d = readTerrain(elev->string(), degrees);
  CHECK(d.positions.size() == 4608u);
  CHECK(d.faces.size() == 8902u);
  CHECK(d.report.nodataCells == 95 * 90 - 4608);
  CHECK(range(d.attributes.get("_ELEVATION").values).lo == 141.0);
  CHECK(range(d.attributes.get("_ELEVATION").values).hi == 547.0);
  CHECK(axis(d.positions, 0).lo >= 5.741666 + 0.5 * 0.008333);
  CHECK(axis(d.positions, 0).hi <= 5.741667 + 94.5 * 0.008334);
  const TerrainMesh m = readTerrain(elev->string());  // local metres: about 50 km across
  CHECK(axis(m.positions, 1).hi - axis(m.positions, 1).lo < 90 * 927.0);
  CHECK(axis(m.positions, 1).hi - axis(m.positions, 1).lo > 50000.0);
  CHECK(buildMesh(m.soup()).report.zeroAreaFaces == 0);

  const auto olinda = sharedData("dem_debian_r_packages/stars/olinda_dem_utm25s.tif");
  GEOSHIFT_SKIP_IF_MISSING(olinda, "dem_debian_r_packages/stars/olinda_dem_utm25s.tif");
  // 111 x 111 float32, no nodata tag, UTM 25S, scale 89.994067 m, tie (0,0) -> (288776.25, 9120760.75):
  // 12321 vertices, 2 * 110 * 110 = 24200 triangles, elevation -1..88 (tifffile).
  const TerrainMesh o = readTerrain(olinda->string());
  CHECK(o.positions.size() == 12321u);
  CHECK(o.faces.size() == 24200u);
  CHECK(range(o.attributes.get("_ELEVATION").values).lo == -1.0);
  CHECK(range(o.attributes.get("_ELEVATION").values).hi == 88.0);
  CHECK(axis(o.positions, 0).lo == Approx(288776.25000080315 + 0.5 * 89.99406734945116));
  CHECK(axis(o.positions, 1).hi == Approx(9120760.750028737 - 0.5 * 89.99406734945116));
  for (const Face& f : o.faces)  // north-up raster: faces still face +z
    CHECK((o.positions[f[1]] - o.positions[f[0]]).cross(o.positions[f[2]] - o.positions[f[0]]).z() > 0);
}

TEST_CASE("LAS 1.3 and 1.4 records written here", "[terrain][las]") {
  const auto dir = tempDir("terrain-las");
  // 1.4, format 7 (class byte at 16, 16-bit colors): values above 255 mean full 16-bit scaling.
  spit(dir / "a.las", lasBytes(4, 7, fourPoints(2, 6)));
  const TerrainPoints a = readLas((dir / "a.las").string());
  REQUIRE(a.positions.size() == 4u);
  CHECK(a.positions[3] == Vec3(1010.0, 2010.0, 4.0));
  CHECK(a.classes == std::vector<int>{2, 6, 2, 6});
  CHECK(a.colors[1].x() == 1.0);
  CHECK(a.colors[3].z() == Approx(32768.0 / 65535.0));
  // 1.3, format 0: class in the low 5 bits, the withheld/keypoint flags above it ignored.
  spit(dir / "b.las", lasBytes(3, 0, fourPoints(2 | 0x80, 1 | 0x40)));
  const TerrainPoints b = readLas((dir / "b.las").string());
  CHECK(b.classes == std::vector<int>{2, 1, 2, 1});
  CHECK(b.colors.empty());
}

TEST_CASE("bad terrain files are refused with the file and the reason", "[terrain][errors]") {
  const auto dir = tempDir("terrain-bad");
  const std::string las = lasBytes(2, 3, fourPoints(2, 1));
  spit(dir / "cut.las", las.substr(0, las.size() - 10));
  std::string msg = errorOf([&] { readLas((dir / "cut.las").string()); });
  CHECK(msg.find("cut.las") != std::string::npos);
  CHECK(msg.find("truncated") != std::string::npos);

  std::string laz = las;
  laz[104] = static_cast<char>(3 | 0x80);
  spit(dir / "c.laz", laz);
  CHECK(errorOf([&] { readTerrain((dir / "c.laz").string()); }).find("LAZ") != std::string::npos);
  spit(dir / "x.las", "LASX" + las.substr(4));
  CHECK(errorOf([&] { readLas((dir / "x.las").string()); }).find("signature") != std::string::npos);
  spit(dir / "short.las", "LASF");
  CHECK(errorOf([&] { readLas((dir / "short.las").string()); }).find("shorter") != std::string::npos);
  std::string fmt = las;
  fmt[104] = 11;
  spit(dir / "f.las", fmt);
  CHECK(errorOf([&] { readLas((dir / "f.las").string()); }).find("format 11") != std::string::npos);

  spit(dir / "p.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nend_header\n" + std::string(20, '\0'));
  msg = errorOf([&] { readPlyPoints((dir / "p.ply").string()); });
  CHECK(msg.find("p.ply") != std::string::npos);
  CHECK(msg.find("truncated") != std::string::npos);
  spit(dir / "q.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n");
  CHECK(errorOf([&] { readPlyPoints((dir / "q.ply").string()); }).find("x, y and z") != std::string::npos);

  spit(dir / "t.tif", "II*\0garbage");
  msg = errorOf([&] { readGeoTiff((dir / "t.tif").string()); });
  CHECK(msg.find("t.tif") != std::string::npos);
  CHECK(errorOf([&] { readTerrain((dir / "missing.las").string()); }).find("missing.las") != std::string::npos);
  CHECK(errorOf([&] { readTerrain((dir / "a.xyz").string()); }).find(".las") != std::string::npos);

  // Three collinear points: the message names the file and the reason.
  spit(dir / "line.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n0 0 0\n1 1 0\n2 2 0\n");
  msg = errorOf([&] { readTerrain((dir / "line.ply").string()); });
  CHECK(msg.find("line.ply") != std::string::npos);
  CHECK(msg.find("collinear") != std::string::npos);
}

TEST_CASE("ASCII PLY with faces and a classification property reads as points", "[terrain][ply]") {
  const auto dir = tempDir("terrain-ply");
  spit(dir / "m.ply", "ply\nformat ascii 1.0\ncomment faces come first here\nelement face 1\n"
                      "property list uchar int vertex_indices\nelement vertex 4\nproperty float x\nproperty float y\n"
                      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                      "property int classification\nend_header\n3 0 1 2\n0 0 1 255 0 0 2\n1 0 1 0 255 0 2\n"
                      "0 1 1 0 0 255 2\n1 1 5 255 255 255 5\n");
  const TerrainPoints p = readPlyPoints((dir / "m.ply").string());
  REQUIRE(p.positions.size() == 4u);
  CHECK(p.classes == std::vector<int>{2, 2, 2, 5});
  CHECK(p.colors[1] == Eigen::Vector3d(0, 1, 0));
  const TerrainMesh m = readTerrain((dir / "m.ply").string());
  CHECK(m.faces.size() == 2u);
  CHECK(m.attributes.get("_HEIGHT_ABOVE_GROUND").values[3] == Approx(4.0));
}

namespace {

// A tiled, uncompressed float32 GeoTIFF built byte by byte (so the reader is checked against the
// TIFF 6.0 and GeoTIFF 1.0 layouts, not against libtiff's writer): 20 x 18 cells in 16 x 16 tiles,
// PixelIsPoint, tie point (0, 0) -> (500000, 4000000), 10 m cells, GDAL_NODATA -9999.
std::string tiledGeoTiff(const std::vector<float>& cells) {
  const int w = 20, h = 18, tile = 16, tiles = 4;
  std::string b(8, '\0');
  b[0] = 'I', b[1] = 'I';
  put<std::uint16_t>(b, 2, 42);
  put<std::uint32_t>(b, 4, 8);
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count, value;
  };
  const int nEntries = 16;
  size_t data = 8 + 2 + 12 * nEntries + 4;
  std::string extra;
  auto place = [&](const void* p, size_t n) {
    const auto at = static_cast<std::uint32_t>(data + extra.size());
    extra.append(static_cast<const char*>(p), n);
    return at;
  };
  const double scale[3] = {10, 10, 0}, tie[6] = {0, 0, 0, 500000, 4000000, 0};
  const std::uint16_t keys[12] = {1, 1, 0, 2, 1024, 0, 1, 1, 1025, 0, 1, 2};
  const char nodata[6] = "-9999";
  const auto scaleAt = place(scale, sizeof scale), tieAt = place(tie, sizeof tie);
  const auto keysAt = place(keys, sizeof keys), nodataAt = place(nodata, sizeof nodata);
  std::uint32_t offsets[tiles], counts[tiles];
  const auto offsetsAt = place(offsets, sizeof offsets), countsAt = place(counts, sizeof counts);
  for (int t = 0; t < tiles; ++t) {
    std::vector<float> px(tile * tile, 0.0f);  // padding beyond the image is ignored by readers
    const int tx = t % 2, ty = t / 2;
    for (int r = 0; r < tile; ++r)
      for (int c = 0; c < tile; ++c) {
        const int col = tx * tile + c, row = ty * tile + r;
        if (col < w && row < h) px[r * tile + c] = cells[row * w + col];
      }
    offsets[t] = place(px.data(), px.size() * 4);
    counts[t] = tile * tile * 4;
  }
  std::memcpy(&extra[offsetsAt - data], offsets, sizeof offsets);
  std::memcpy(&extra[countsAt - data], counts, sizeof counts);
  const Entry entries[nEntries] = {
      {256, 4, 1, static_cast<std::uint32_t>(w)}, {257, 4, 1, static_cast<std::uint32_t>(h)}, {258, 3, 1, 32},
      {259, 3, 1, 1}, {262, 3, 1, 1}, {277, 3, 1, 1}, {284, 3, 1, 1}, {322, 3, 1, tile}, {323, 3, 1, tile},
      {324, 4, tiles, offsetsAt}, {325, 4, tiles, countsAt}, {339, 3, 1, 3}, {33550, 12, 3, scaleAt},
      {33922, 12, 6, tieAt}, {34735, 3, 12, keysAt}, {42113, 2, 6, nodataAt}};
  std::string ifd(2 + 12 * nEntries + 4, '\0');
  put<std::uint16_t>(ifd, 0, nEntries);
  for (int i = 0; i < nEntries; ++i) {
    put(ifd, 2 + 12 * i, entries[i].tag), put(ifd, 4 + 12 * i, entries[i].type);
    put(ifd, 6 + 12 * i, entries[i].count), put(ifd, 10 + 12 * i, entries[i].value);
  }
  return b + ifd + extra;
}

}  // namespace

TEST_CASE("tiled float GeoTIFF with PixelIsPoint and nodata", "[terrain][geotiff]") {
  const auto dir = tempDir("terrain-tif");
  std::vector<float> cells(20 * 18);
  for (int r = 0; r < 18; ++r)
    for (int c = 0; c < 20; ++c) cells[r * 20 + c] = 0.5f * c - 0.25f * r + 50.0f;
  cells[0] = -9999.0f;               // nodata corner
  cells[5 * 20 + 17] = NAN;          // NaN is nodata too (across the tile border at column 16)
  spit(dir / "t.tif", tiledGeoTiff(cells));
  const ElevationGrid g = readGeoTiff((dir / "t.tif").string());
  REQUIRE(g.width == 20);
  REQUIRE(g.height == 18);
  CHECK(!g.geographic);
  CHECK(std::isnan(g.values[0]));
  CHECK(std::isnan(g.values[5 * 20 + 17]));
  CHECK(g.values[17 * 20 + 19] == 0.5 * 19 - 0.25 * 17 + 50.0);  // last cell, in the fourth tile
  const TerrainMesh m = gridTerrain(g);
  CHECK(m.positions.size() == 20u * 18u - 2u);
  // Brute-force face count: quads with 4 valid corners give 2, with 3 give 1.
  CHECK(m.faces.size() == 2u * 19u * 17u - 1u - 4u);
  // PixelIsPoint: cell (col, row) is centred at the tie point plus (10 col, -10 row).
  CHECK(m.positions[0] == Vec3(500010.0, 4000000.0, 50.5));
  CHECK(m.positions.back() == Vec3(500190.0, 3999830.0, 0.5 * 19 - 0.25 * 17 + 50.0));
}

TEST_CASE("cut or lying terrain files never crash: InputError naming the file", "[terrain][errors]") {
  const auto simple = sharedData("pdal_testdata/las/simple.las");
  GEOSHIFT_SKIP_IF_MISSING(simple, "pdal_testdata/las/simple.las");
  const auto dir = tempDir("terrain-cuts");
  const std::string las = slurp(*simple);
  for (size_t n : {size_t(0), size_t(100), size_t(226), size_t(227), size_t(500), las.size() - 1}) {
    spit(dir / "cut.las", las.substr(0, n));
    CHECK(errorOf([&] { readTerrain((dir / "cut.las").string()); }).find("cut.las") != std::string::npos);
  }
  spit(dir / "huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\nproperty double x\n"
                         "property double y\nproperty double z\nend_header\n" + std::string(64, '\0'));
  CHECK(errorOf([&] { readPlyPoints((dir / "huge.ply").string()); }).find("truncated") != std::string::npos);
}

// Regression tests for the defects the fuzz harnesses found, or that writing them did (fuzz/,
// scripts/fuzz.sh, docs/io.md#fuzzing): each input is rebuilt here from what made it fail, small
// enough to read, and must now give a clean error or a correct result.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "geoshift/error.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/terrain.hpp"
#include "support.hpp"

using namespace geoshift;
using namespace geoshift::test;
using Catch::Matchers::Contains;

namespace {

// A little-endian TIFF with one IFD at byte 8 of (tag, type, value, count) entries whose values fit
// in 4 bytes (stored inline), then `tail` bytes of zeros where the strip or tile data would be, at
// dataOffset(entries).
struct TiffEntry {
  std::uint16_t tag, type;
  std::uint32_t value;
  std::uint32_t count = 1;
};

std::uint32_t dataOffset(size_t entries) { return static_cast<std::uint32_t>(8 + 2 + 12 * entries + 4); }

std::string tiffBytes(std::vector<TiffEntry> entries, size_t tail) {
  std::string b = std::string("II*\0", 4) + std::string("\x08\0\0\0", 4);
  auto put = [&](auto v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(static_cast<std::uint16_t>(entries.size()));
  for (const TiffEntry& e : entries) {
    put(e.tag), put(e.type), put(e.count);
    if (e.type == 3 && e.count == 1) put(static_cast<std::uint16_t>(e.value)), put(std::uint16_t{0});
    else put(e.value);
  }
  put(std::uint32_t{0});
  b.append(tail, '\0');
  return b;
}

// One 8-bit strip of `bytes` bytes right after the IFD, and `extra` entries (tags above 279).
std::string stripTiff(std::uint32_t width, std::uint32_t height, std::uint16_t compression, std::uint32_t bytes,
                      const std::vector<TiffEntry>& extra = {}) {
  std::vector<TiffEntry> e = {{256, 4, width}, {257, 4, height}, {258, 3, 8},  {259, 3, compression}, {262, 3, 1},
                              {273, 4, 0},     {277, 3, 1},      {278, 4, height}, {279, 4, bytes}};
  e.insert(e.end(), extra.begin(), extra.end());
  e[5].value = dataOffset(e.size());
  return tiffBytes(e, bytes);
}

}  // namespace

TEST_CASE("GeoTIFF: pixels a file declares are checked against the bytes it holds before allocating",
          "[io][terrain][geotiff][fuzz]") {
  const auto dir = tempDir("io-fuzz-tiff");
  // 132 bytes declaring 16384 x 16384 8-bit pixels in one uncompressed strip of 10 bytes: the
  // reader used to allocate 2 GB of cells (and a 256 MB strip) before libtiff found the data short.
  spit(dir / "huge.tif", stripTiff(16384, 16384, 1, 10));
  CHECK(std::filesystem::file_size(dir / "huge.tif") == 132);  // 122 bytes of header and IFD
  // (libtiff estimates the byte count of a single uncompressed strip that is too short for it: the
  // rest of the file, 10 bytes here, 132 at most.)
  const std::string huge = errorOf([&] { readGeoTiff((dir / "huge.tif").string()); });
  CHECK_THAT(huge, Contains("huge.tif: 16384 x 16384 pixels of 8-bit samples need 268435456 bytes of strips, more than "
                            "the ") &&
                       Contains(" bytes of them in the file can hold (compression 1)"));
  // Deflate decodes at most 1032 bytes per stored byte: 100 bytes cannot hold 268 MB either.
  spit(dir / "deflate.tif", stripTiff(16384, 16384, 8, 100));
  CHECK_THAT(errorOf([&] { readGeoTiff((dir / "deflate.tif").string()); }),
             Contains("more than the 100 bytes of them in the file can hold (compression 8)"));
  // Tiles count whole: one 4096 x 4096 tile for a 1 x 1 image needs 16 MB of decoded bytes.
  spit(dir / "tile.tif", tiffBytes({{256, 4, 1}, {257, 4, 1}, {258, 3, 8}, {259, 3, 1}, {262, 3, 1}, {277, 3, 1},
                                    {322, 4, 4096}, {323, 4, 4096}, {324, 4, dataOffset(10)}, {325, 4, 16}},
                                   16));
  CHECK_THAT(errorOf([&] { readGeoTiff((dir / "tile.tif").string()); }),
             Contains("1 x 1 pixels of 8-bit samples need 16777216 bytes of tiles, more than the 16 bytes"));
  // The same layout with all its bytes present reads: 4 x 3 zeros.
  spit(dir / "small.tif", stripTiff(4, 3, 1, 12));
  const ElevationGrid g = readGeoTiff((dir / "small.tif").string());
  CHECK(g.width == 4);
  CHECK(g.height == 3);
  CHECK(g.values == std::vector<double>(12, 0.0));
}

TEST_CASE("welding with a tolerance copes with coordinates far beyond its grid", "[mesh][weld][fuzz]") {
  // fuzz_soup's seed `huge` welded with tolerance 0.3: 1e308 / 0.3 overflowed the grid cell's 64-bit
  // index (undefined behaviour). Cells are clamped now; the distance test still decides what merges.
  const std::vector<Vec3> p = {{0, 0, 0}, {1e308, 0, 0}, {0.1, 0, 0}, {1e308, 0, 0}, {-1e308, 1e308, 0}, {2, 0, 0}};
  WeldOptions o;
  o.tolerance = 0.3;
  const Weld w = weld(p, o);
  CHECK(w.vertexOf == std::vector<int>{0, 1, 0, 1, 2, 3});
  CHECK(w.mergedCount == 2);
  // A far cell is shared by points that are not within the tolerance: they stay apart.
  const Weld far = weld({{1e300, 0, 0}, {2e300, 0, 0}}, o);
  CHECK(far.vertexOf == std::vector<int>{0, 1});
  o.tolerance = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(errorOf([&] { weld(p, o); }), Contains("weld tolerance must be a finite number"));
  // Built into a mesh: the near corner welds, the far vertex stays, isolated.
  MeshBuildOptions b;
  b.weldOptions.tolerance = 0.3;
  const MeshBuild m = buildMesh({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.1, 0, 0}, {1e308, 1e308, -1e308}},
                                 {{0, 1, 2}, {3, 2, 1}}},
                                b);
  CHECK(m.vertexOf == std::vector<int>{0, 1, 2, 0, 3});
  CHECK(m.mesh.faceCount() == 2);
  CHECK(m.mesh.isIsolated(3));
}

TEST_CASE("GeoTIFF: georeferencing tags stored with another type are errors, not read at the wrong size",
          "[io][terrain][geotiff][fuzz]") {
  const auto dir = tempDir("io-fuzz-tiff-tags");
  // fuzz_tif: ModelTiepoint (33922) stored as 4 ASCII bytes was read as 4 doubles (32 bytes), past
  // the end of libtiff's copy of the tag (heap-buffer-overflow under AddressSanitizer).
  const std::uint32_t abc = 'a' | 'b' << 8 | 'c' << 16;
  spit(dir / "tie.tif", stripTiff(4, 3, 1, 12, {{33922, 2, abc, 4}}));
  CHECK_THAT(errorOf([&] { readGeoTiff((dir / "tie.tif").string()); }),
             Contains("tie.tif: GeoTIFF tag 33922 (ModelTiepoint) is stored as TIFF type 2; GeoTIFF stores it as DOUBLE (12)"));
  // The key directory as LONGs instead of SHORTs.
  spit(dir / "keys.tif", stripTiff(4, 3, 1, 12, {{34735, 4, 1}}));
  CHECK_THAT(errorOf([&] { readGeoTiff((dir / "keys.tif").string()); }),
             Contains("GeoTIFF tag 34735 (GeoKeyDirectory) is stored as TIFF type 4; GeoTIFF stores it as SHORT (3)"));
}

TEST_CASE("GeoTIFF: a text tag without a terminating NUL is read to its count, not past it",
          "[io][terrain][geotiff][fuzz]") {
  const auto dir = tempDir("io-fuzz-tiff-ascii");
  // fuzz_tif: GDAL_NODATA (42113) stored as 4 UNDEFINED bytes (type 7, so libtiff adds no NUL as
  // it does for ASCII); the reader took it as a C string and strlen read past libtiff's 4-byte copy
  // (heap-buffer-overflow).
  const std::uint32_t zeros = '0' | '0' << 8 | '0' << 16 | '0' << 24;
  spit(dir / "nodata.tif", stripTiff(4, 3, 1, 12, {{42113, 7, zeros, 4}}));
  const ElevationGrid g = readGeoTiff((dir / "nodata.tif").string());
  REQUIRE(g.values.size() == 12);
  // "0000" is the nodata value: every cell (all zeros) is nodata.
  for (double v : g.values) CHECK(std::isnan(v));
}

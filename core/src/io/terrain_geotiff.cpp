// DEM GeoTIFFs through libtiff. The GeoTIFF part is three tags and two geo keys, read here
// directly: libgeotiff would add PROJ, its data and curl to the install for no benefit, since
// geoshift does not reproject.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <type_traits>

#include <tiffio.h>

#include "geoshift/terrain.hpp"
#include "io_detail.hpp"

namespace geoshift {
namespace {

constexpr uint32_t kPixelScale = 33550, kTiepoint = 33922, kTransformation = 34264, kGeoKeys = 34735;

// libtiff reports through handlers; these collect the messages of one file for our error.
int onError(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  char buf[512];
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  auto& msg = *static_cast<std::string*>(user);
  if (msg.empty()) msg = std::string(module ? module : "libtiff") + ": " + buf;
  return 1;
}
int onWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }  // unknown tags etc.

struct Closer {
  void operator()(TIFF* t) const { TIFFClose(t); }
};

// Reads a tag's array whatever way libtiff registered it (known or anonymous field). libtiff does
// not know the GeoTIFF tags, so it registers them with the type the file gives: a tag stored with
// another type than GeoTIFF's (DOUBLE for the matrices, SHORT for the keys) is an error, not
// values read at the wrong size.
template <class T>
std::vector<T> getArray(TIFF* tif, uint32_t tag, const char* name, const std::string& path) {
  const TIFFField* f = TIFFFindField(tif, tag, TIFF_ANY);
  if (!f) return {};
  const TIFFDataType want = std::is_same_v<T, double> ? TIFF_DOUBLE : TIFF_SHORT;
  if (TIFFFieldDataType(f) != want || TIFFFieldSetGetSize(f) != static_cast<int>(sizeof(T)))
    io::fail(path, std::string("GeoTIFF tag ") + std::to_string(tag) + " (" + name + ") is stored as TIFF type " +
                       std::to_string(static_cast<int>(TIFFFieldDataType(f))) + "; GeoTIFF stores it as " +
                       (want == TIFF_DOUBLE ? "DOUBLE (12)" : "SHORT (3)"));
  void* data = nullptr;
  uint32_t n = 0;
  if (TIFFFieldPassCount(f)) {
    if (TIFFFieldReadCount(f) == TIFF_VARIABLE2) {
      if (!TIFFGetField(tif, tag, &n, &data)) return {};
    } else {
      uint16_t n16 = 0;
      if (!TIFFGetField(tif, tag, &n16, &data)) return {};
      n = n16;
    }
  } else {
    return {};
  }
  const T* p = static_cast<const T*>(data);
  return data ? std::vector<T>(p, p + n) : std::vector<T>{};
}

std::string getAscii(TIFF* tif, uint32_t tag) {
  const TIFFField* f = TIFFFindField(tif, tag, TIFF_ANY);
  if (!f) return {};
  char* s = nullptr;
  if (TIFFFieldPassCount(f)) {
    // A counted value is the file's bytes as stored: nothing guarantees a terminating NUL (a
    // fuzzed file without one made strlen read past the buffer), so the count bounds it.
    uint32_t n = 0;
    uint16_t n16 = 0;
    const bool wide = TIFFFieldReadCount(f) == TIFF_VARIABLE2;
    const bool ok = wide ? TIFFGetField(tif, tag, &n, &s) : TIFFGetField(tif, tag, &n16, &s);
    if (!ok || !s) return {};
    return std::string(s, ::strnlen(s, wide ? n : n16));
  }
  if (!TIFFGetField(tif, tag, &s)) return {};
  return s ? std::string(s) : std::string();
}

// The most bytes one stored byte can decode to under a compression scheme, so that what a file
// declares (pixels x sample size) is checked against the bytes it holds before anything is
// allocated: a 200-byte file cannot make us allocate gigabytes. PackBits repeats one byte at most
// 128 times for a 2-byte run; an LZW code (9 bits or more) emits at most 4096 bytes; zlib's
// deflate stops at 1032:1. Other codecs (LZMA, ZSTD, JPEG, ...) get a generous 2^16.
double maxExpansion(uint16_t compression) {
  switch (compression) {
    case COMPRESSION_NONE: return 1;
    case COMPRESSION_PACKBITS: return 64;
    case COMPRESSION_LZW: return 3641;  // 4096 bytes per 9 bits
    case COMPRESSION_ADOBE_DEFLATE:
    case COMPRESSION_DEFLATE: return 1032;
    default: return 65536;
  }
}

// Bytes of strip or tile data the file holds: the byte counts, each clipped to the file's size.
double storedBytes(TIFF* t, bool tiled, double fileSize) {
  uint64_t* counts = nullptr;
  if (!TIFFGetField(t, tiled ? TIFFTAG_TILEBYTECOUNTS : TIFFTAG_STRIPBYTECOUNTS, &counts) || !counts) return 0;
  const uint32_t n = tiled ? TIFFNumberOfTiles(t) : TIFFNumberOfStrips(t);
  double sum = 0;
  for (uint32_t i = 0; i < n; ++i) sum += std::min(static_cast<double>(counts[i]), fileSize);
  return std::min(sum, fileSize);
}

// How the raster's samples are stored.
struct Layout {
  uint32_t w = 0, h = 0;
  uint16_t bits = 0, spp = 1, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG;
  size_t bytes() const { return bits / 8; }
  size_t stride() const { return planar == PLANARCONFIG_CONTIG ? spp : 1; }  // samples per pixel in a block
};

// The image's size and sample type; InputError for no pixels, too many, or samples it cannot read.
Layout readLayout(TIFF* t, const std::string& path) {
  Layout l;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &l.w);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &l.h);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &l.bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &l.spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &l.format);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &l.planar);
  if (l.w == 0 || l.h == 0) io::fail(path, "image has no pixels");
  if (static_cast<uint64_t>(l.w) * l.h > (1u << 28))
    io::fail(path, std::to_string(l.w) + " x " + std::to_string(l.h) +
                       " pixels is too large (at most 2^28 cells; crop or resample it first)");
  const bool okFormat = (l.format == SAMPLEFORMAT_UINT || l.format == SAMPLEFORMAT_INT)
                            ? (l.bits == 8 || l.bits == 16 || l.bits == 32 || l.bits == 64)
                            : l.format == SAMPLEFORMAT_IEEEFP && (l.bits == 32 || l.bits == 64);
  if (!okFormat || l.spp < 1)
    io::fail(path, "unsupported samples: " + std::to_string(l.bits) + "-bit, sample format " + std::to_string(l.format) +
                       " (8-64 bit integers and 32/64-bit floats are supported)");
  return l;
}

// Decoded bytes the blocks declare (tiles are whole even where they overhang the image), against
// what the stored bytes can decode to: a small file cannot make the reader allocate gigabytes.
void checkDeclaredSize(TIFF* t, const std::string& path, const Layout& l) {
  const bool tiled = TIFFIsTiled(t);
  uint16_t compression = COMPRESSION_NONE;
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
  const double declared = tiled ? static_cast<double>(TIFFNumberOfTiles(t)) * static_cast<double>(TIFFTileSize64(t))
                                : static_cast<double>(l.w) * l.h * l.bytes() * (l.planar == PLANARCONFIG_CONTIG ? l.spp : 1);
  std::error_code ec;
  const auto fileSize = std::filesystem::file_size(path, ec);
  const double stored = storedBytes(t, tiled, ec ? 0.0 : static_cast<double>(fileSize));
  if (declared > maxExpansion(compression) * stored)
    io::fail(path, std::to_string(l.w) + " x " + std::to_string(l.h) + " pixels of " + std::to_string(l.bits) +
                       "-bit samples need " + formatNumber(declared) + " bytes of " + (tiled ? "tiles" : "strips") +
                       ", more than the " + formatNumber(stored) + " bytes of them in the file can hold (compression " +
                       std::to_string(compression) + ")");
}

double sampleAt(const Layout& l, const unsigned char* p) {
  switch (l.format) {
    case SAMPLEFORMAT_IEEEFP:
      if (l.bits == 32) { float v; std::memcpy(&v, p, 4); return v; }
      { double v; std::memcpy(&v, p, 8); return v; }
    case SAMPLEFORMAT_INT:
      switch (l.bits) {
        case 8: return static_cast<int8_t>(*p);
        case 16: { int16_t v; std::memcpy(&v, p, 2); return v; }
        case 32: { int32_t v; std::memcpy(&v, p, 4); return v; }
        default: { int64_t v; std::memcpy(&v, p, 8); return static_cast<double>(v); }
      }
    default:
      switch (l.bits) {
        case 8: return *p;
        case 16: { uint16_t v; std::memcpy(&v, p, 2); return v; }
        case 32: { uint32_t v; std::memcpy(&v, p, 4); return v; }
        default: { uint64_t v; std::memcpy(&v, p, 8); return static_cast<double>(v); }
      }
  }
}

// Band 1 of every tile or strip into g.values; `error` holds libtiff's last message.
void readPixels(TIFF* t, const std::string& path, const Layout& l, const std::string& error, ElevationGrid& g) {
  const uint32_t w = l.w, h = l.h;
  const size_t bytes = l.bytes(), stride = l.stride();
  auto fail = [&](const std::string& what) { io::fail(path, what + (error.empty() ? "" : ": " + error)); };
  // Copies a decoded block of bw x bh pixels whose top-left pixel is (x0, y0).
  auto copyBlock = [&](const std::vector<unsigned char>& buf, uint32_t x0, uint32_t y0, uint32_t bw, uint32_t bh) {
    for (uint32_t r = 0; r < bh && y0 + r < h; ++r)
      for (uint32_t c = 0; c < bw && x0 + c < w; ++c)
        g.values[static_cast<size_t>(y0 + r) * w + x0 + c] = sampleAt(l, buf.data() + (static_cast<size_t>(r) * bw + c) * stride * bytes);
  };
  if (TIFFIsTiled(t)) {
    uint32_t tw = 0, th = 0;
    TIFFGetField(t, TIFFTAG_TILEWIDTH, &tw);
    TIFFGetField(t, TIFFTAG_TILELENGTH, &th);
    if (tw == 0 || th == 0) io::fail(path, "tiled image without tile size");
    std::vector<unsigned char> buf(static_cast<size_t>(TIFFTileSize(t)));
    if (buf.size() < static_cast<size_t>(tw) * th * stride * bytes) io::fail(path, "tile size inconsistent with the tile dimensions");
    for (uint32_t y = 0; y < h; y += th)
      for (uint32_t x = 0; x < w; x += tw) {
        if (TIFFReadEncodedTile(t, TIFFComputeTile(t, x, y, 0, 0), buf.data(), static_cast<tmsize_t>(buf.size())) < 0)
          fail("cannot decode the tile at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        copyBlock(buf, x, y, tw, th);
      }
  } else {
    uint32_t rps = h;
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &rps);
    rps = std::min(std::max(rps, 1u), h);
    std::vector<unsigned char> buf(static_cast<size_t>(TIFFStripSize(t)));
    if (buf.size() < static_cast<size_t>(w) * rps * stride * bytes) io::fail(path, "strip size inconsistent with the image width");
    for (uint32_t y = 0; y < h; y += rps) {
      if (TIFFReadEncodedStrip(t, TIFFComputeStrip(t, y, 0), buf.data(), static_cast<tmsize_t>(buf.size())) < 0)
        fail("cannot decode the strip at row " + std::to_string(y));
      copyBlock(buf, 0, y, w, rps);
    }
  }
}

// nodata: GDAL's tag, compared in the samples' own precision; NaN cells are nodata as well.
void applyNodata(TIFF* t, const std::string& path, const Layout& l, ElevationGrid& g) {
  const std::string nodataText = getAscii(t, TIFFTAG_GDAL_NODATA);
  if (nodataText.empty()) return;
  char* end = nullptr;
  double nodata = std::strtod(nodataText.c_str(), &end);
  if (end == nodataText.c_str()) io::fail(path, "GDAL_NODATA '" + nodataText + "' is not a number");
  if (l.format == SAMPLEFORMAT_IEEEFP && l.bits == 32) nodata = static_cast<float>(nodata);
  for (double& v : g.values)
    if (v == nodata) v = std::nan("");
}

// The cell-to-model transform from ModelTransformation, else ModelPixelScale and the first
// ModelTiepoint (cell corners; PixelIsPoint rasters name cell centres), and whether it is geographic.
void georeference(TIFF* t, const std::string& path, ElevationGrid& g) {
  const auto keys = getArray<uint16_t>(t, kGeoKeys, "GeoKeyDirectory", path);
  int modelType = 0, rasterType = 1;
  if (keys.size() >= 4) {
    const size_t nk = std::min<size_t>(keys[3], (keys.size() - 4) / 4);
    for (size_t k = 0; k < nk; ++k) {
      const uint16_t* e = keys.data() + 4 + 4 * k;
      if (e[1] != 0) continue;  // the two keys we need are stored inline
      if (e[0] == 1024) modelType = e[3];
      if (e[0] == 1025) rasterType = e[3];
    }
  }
  g.geographic = modelType == 2;
  const double shift = rasterType == 2 ? 0.5 : 0.0;  // PixelIsPoint: tie points name cell centres
  const auto scale = getArray<double>(t, kPixelScale, "ModelPixelScale", path);
  const auto tie = getArray<double>(t, kTiepoint, "ModelTiepoint", path);
  const auto m = getArray<double>(t, kTransformation, "ModelTransformation", path);
  if (m.size() >= 16) {
    g.transform = {m[3], m[0], m[1], m[7], m[4], m[5]};
    g.transform[0] -= shift * (m[0] + m[1]);
    g.transform[3] -= shift * (m[4] + m[5]);
  } else if (scale.size() >= 2 && tie.size() >= 6) {
    if (tie.size() > 6) g.notes.push_back("GeoTIFF has several tie points; the first one is used");
    g.transform = {tie[3] - (tie[0] + shift) * scale[0], scale[0], 0.0, tie[4] + (tie[1] + shift) * scale[1], 0.0, -scale[1]};
  } else {
    g.notes.push_back("not georeferenced (no ModelPixelScale/ModelTiepoint or ModelTransformation): cells 1 unit apart");
  }
}

}  // namespace

ElevationGrid readGeoTiff(const std::string& path) {
  std::string error;
  TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(opts, onError, &error);
  TIFFOpenOptionsSetWarningHandlerExtR(opts, onWarning, nullptr);
  std::unique_ptr<TIFF, Closer> tif(TIFFOpenExt(path.c_str(), "r", opts));
  TIFFOpenOptionsFree(opts);
  if (!tif) io::fail(path, "cannot open as TIFF" + (error.empty() ? std::string() : " (" + error + ")"));
  TIFF* t = tif.get();

  const Layout layout = readLayout(t, path);
  checkDeclaredSize(t, path, layout);
  ElevationGrid g;
  g.width = static_cast<int>(layout.w);
  g.height = static_cast<int>(layout.h);
  g.values.assign(static_cast<size_t>(layout.w) * layout.h, std::nan(""));
  if (layout.spp > 1) g.notes.push_back("the raster has " + std::to_string(layout.spp) + " bands; band 1 is the elevation");
  readPixels(t, path, layout, error, g);
  applyNodata(t, path, layout, g);
  georeference(t, path, g);
  if (TIFFNumberOfDirectories(t) > 1) g.notes.push_back("only the first image of the TIFF is read");
  return g;
}

}  // namespace geoshift

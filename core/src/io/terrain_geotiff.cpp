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

}  // namespace

ElevationGrid readGeoTiff(const std::string& path) {
  std::string error;
  TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(opts, onError, &error);
  TIFFOpenOptionsSetWarningHandlerExtR(opts, onWarning, nullptr);
  std::unique_ptr<TIFF, Closer> tif(TIFFOpenExt(path.c_str(), "r", opts));
  TIFFOpenOptionsFree(opts);
  auto fail = [&](const std::string& what) { io::fail(path, what); };
  if (!tif) fail("cannot open as TIFF" + (error.empty() ? std::string() : " (" + error + ")"));
  TIFF* t = tif.get();

  uint32_t w = 0, h = 0;
  uint16_t bits = 0, spp = 1, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &planar);
  if (w == 0 || h == 0) fail("image has no pixels");
  if (static_cast<uint64_t>(w) * h > (1u << 28))
    fail(std::to_string(w) + " x " + std::to_string(h) + " pixels is too large (at most 2^28 cells; crop or resample it first)");
  const bool okFormat = (format == SAMPLEFORMAT_UINT || format == SAMPLEFORMAT_INT)
                            ? (bits == 8 || bits == 16 || bits == 32 || bits == 64)
                            : format == SAMPLEFORMAT_IEEEFP && (bits == 32 || bits == 64);
  if (!okFormat || spp < 1)
    fail("unsupported samples: " + std::to_string(bits) + "-bit, sample format " + std::to_string(format) +
         " (8-64 bit integers and 32/64-bit floats are supported)");

  // Decoded bytes the blocks declare (tiles are whole even where they overhang the image), against
  // what the stored bytes can decode to.
  const bool tiled = TIFFIsTiled(t);
  uint16_t compression = COMPRESSION_NONE;
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
  const double declared = tiled ? static_cast<double>(TIFFNumberOfTiles(t)) * static_cast<double>(TIFFTileSize64(t))
                                : static_cast<double>(w) * h * (bits / 8) * (planar == PLANARCONFIG_CONTIG ? spp : 1);
  std::error_code ec;
  const auto fileSize = std::filesystem::file_size(path, ec);
  const double stored = storedBytes(t, tiled, ec ? 0.0 : static_cast<double>(fileSize));
  if (declared > maxExpansion(compression) * stored)
    fail(std::to_string(w) + " x " + std::to_string(h) + " pixels of " + std::to_string(bits) + "-bit samples need " +
         io::formatNumber(declared) + " bytes of " + (tiled ? "tiles" : "strips") + ", more than the " + io::formatNumber(stored) +
         " bytes of them in the file can hold (compression " + std::to_string(compression) + ")");

  ElevationGrid g;
  g.width = static_cast<int>(w);
  g.height = static_cast<int>(h);
  g.values.assign(static_cast<size_t>(w) * h, std::nan(""));
  if (spp > 1) g.notes.push_back("the raster has " + std::to_string(spp) + " bands; band 1 is the elevation");

  const size_t bytes = bits / 8;
  const size_t stride = planar == PLANARCONFIG_CONTIG ? spp : 1;
  auto sample = [&](const unsigned char* p) -> double {
    switch (format) {
      case SAMPLEFORMAT_IEEEFP:
        if (bits == 32) { float v; std::memcpy(&v, p, 4); return v; }
        { double v; std::memcpy(&v, p, 8); return v; }
      case SAMPLEFORMAT_INT:
        switch (bits) {
          case 8: return static_cast<int8_t>(*p);
          case 16: { int16_t v; std::memcpy(&v, p, 2); return v; }
          case 32: { int32_t v; std::memcpy(&v, p, 4); return v; }
          default: { int64_t v; std::memcpy(&v, p, 8); return static_cast<double>(v); }
        }
      default:
        switch (bits) {
          case 8: return *p;
          case 16: { uint16_t v; std::memcpy(&v, p, 2); return v; }
          case 32: { uint32_t v; std::memcpy(&v, p, 4); return v; }
          default: { uint64_t v; std::memcpy(&v, p, 8); return static_cast<double>(v); }
        }
    }
  };
  // Copies a decoded block of bw x bh pixels whose top-left pixel is (x0, y0).
  auto copyBlock = [&](const std::vector<unsigned char>& buf, uint32_t x0, uint32_t y0, uint32_t bw, uint32_t bh) {
    for (uint32_t r = 0; r < bh && y0 + r < h; ++r)
      for (uint32_t c = 0; c < bw && x0 + c < w; ++c)
        g.values[static_cast<size_t>(y0 + r) * w + x0 + c] = sample(buf.data() + (static_cast<size_t>(r) * bw + c) * stride * bytes);
  };
  if (TIFFIsTiled(t)) {
    uint32_t tw = 0, th = 0;
    TIFFGetField(t, TIFFTAG_TILEWIDTH, &tw);
    TIFFGetField(t, TIFFTAG_TILELENGTH, &th);
    if (tw == 0 || th == 0) fail("tiled image without tile size");
    std::vector<unsigned char> buf(static_cast<size_t>(TIFFTileSize(t)));
    if (buf.size() < static_cast<size_t>(tw) * th * stride * bytes) fail("tile size inconsistent with the tile dimensions");
    for (uint32_t y = 0; y < h; y += th)
      for (uint32_t x = 0; x < w; x += tw) {
        if (TIFFReadEncodedTile(t, TIFFComputeTile(t, x, y, 0, 0), buf.data(), static_cast<tmsize_t>(buf.size())) < 0)
          fail("cannot decode the tile at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")" +
               (error.empty() ? "" : ": " + error));
        copyBlock(buf, x, y, tw, th);
      }
  } else {
    uint32_t rps = h;
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &rps);
    rps = std::min(std::max(rps, 1u), h);
    std::vector<unsigned char> buf(static_cast<size_t>(TIFFStripSize(t)));
    if (buf.size() < static_cast<size_t>(w) * rps * stride * bytes) fail("strip size inconsistent with the image width");
    for (uint32_t y = 0; y < h; y += rps) {
      if (TIFFReadEncodedStrip(t, TIFFComputeStrip(t, y, 0), buf.data(), static_cast<tmsize_t>(buf.size())) < 0)
        fail("cannot decode the strip at row " + std::to_string(y) + (error.empty() ? "" : ": " + error));
      copyBlock(buf, 0, y, w, rps);
    }
  }

  // nodata: GDAL's tag, compared in the samples' own precision; NaN cells are nodata as well.
  const std::string nodataText = getAscii(t, TIFFTAG_GDAL_NODATA);
  if (!nodataText.empty()) {
    char* end = nullptr;
    double nodata = std::strtod(nodataText.c_str(), &end);
    if (end == nodataText.c_str()) fail("GDAL_NODATA '" + nodataText + "' is not a number");
    if (format == SAMPLEFORMAT_IEEEFP && bits == 32) nodata = static_cast<float>(nodata);
    for (double& v : g.values)
      if (v == nodata) v = std::nan("");
  }

  // Georeferencing.
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
  if (TIFFNumberOfDirectories(t) > 1) g.notes.push_back("only the first image of the TIFF is read");
  return g;
}

}  // namespace geoshift

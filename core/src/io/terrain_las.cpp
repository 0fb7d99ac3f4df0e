// LAS 1.0-1.4 point records (ASPRS LAS specification R15). Our own reader: Debian 12 packages
// no LAS library (no PDAL, libLAS or LASzip), and uncompressed records are fixed-size
// little-endian structs, so a bounds-checked reader of the few fields needed is the light option.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "geoshift/terrain.hpp"
#include "io_detail.hpp"

namespace geoshift {
namespace {

template <class T>
T le(const std::string& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);  // LAS is little-endian, as every target we build for
  return v;
}

struct Layout {
  size_t minLength;
  size_t rgbOffset;  // 0: none
  bool extended;     // formats 6-10: classification byte at 16
};

Layout layoutOf(int format) {
  switch (format) {
    case 0: return {20, 0, false};
    case 1: return {28, 0, false};
    case 2: return {26, 20, false};
    case 3: return {34, 28, false};
    case 4: return {57, 0, false};
    case 5: return {63, 28, false};
    case 6: return {30, 0, true};
    case 7: return {36, 30, true};
    case 8: return {38, 30, true};
    case 9: return {59, 0, true};
    case 10: return {67, 30, true};
    default: return {0, 0, false};
  }
}

}  // namespace

TerrainPoints readLas(const std::string& path) {
  const std::string b = io::readWholeFile(path);
  auto fail = [&](const std::string& what) { io::fail(path, what); };
  if (b.size() < 227) fail("not a LAS file: " + std::to_string(b.size()) + " bytes, shorter than a LAS header (227)");
  if (b.compare(0, 4, "LASF") != 0) fail("not a LAS file (no 'LASF' signature)");
  const int major = static_cast<unsigned char>(b[24]), minor = static_cast<unsigned char>(b[25]);
  if (major != 1 || minor > 4)
    fail("LAS version " + std::to_string(major) + "." + std::to_string(minor) + " is not supported (1.0-1.4 are)");
  const auto headerSize = le<std::uint16_t>(b, 94);
  const auto offset = le<std::uint32_t>(b, 96);
  const int formatByte = static_cast<unsigned char>(b[104]);
  const auto recordLength = le<std::uint16_t>(b, 105);
  std::uint64_t count = le<std::uint32_t>(b, 107);
  if (formatByte & 0xC0)
    fail("compressed LAS (LAZ, point format byte " + std::to_string(formatByte) +
         ") is not supported: no LASzip library is packaged in Debian 12; decompress it first (e.g. laszip -i in.laz -o out.las)");
  if (minor >= 4) {
    if (b.size() < 375 || headerSize < 375) fail("LAS 1.4 header is shorter than 375 bytes");
    const auto count64 = le<std::uint64_t>(b, 247);
    if (count == 0 || count64 != 0) count = count64;  // the legacy count is 0 when it does not fit
  }
  if (headerSize < 227 || headerSize > b.size()) fail("header size " + std::to_string(headerSize) + " is invalid");
  const Layout layout = layoutOf(formatByte);
  if (layout.minLength == 0) fail("point data format " + std::to_string(formatByte) + " is not a LAS format (0-10)");
  if (recordLength < layout.minLength)
    fail("point format " + std::to_string(formatByte) + " needs records of at least " + std::to_string(layout.minLength) +
         " bytes, the header says " + std::to_string(recordLength));
  if (offset < headerSize) fail("point data offset " + std::to_string(offset) + " lies inside the header");
  const std::uint64_t needed = offset + count * recordLength;
  if (count > (std::uint64_t(1) << 31) || needed > b.size())
    fail("truncated: the header announces " + std::to_string(count) + " points of " + std::to_string(recordLength) +
         " bytes from offset " + std::to_string(offset) + " (" + std::to_string(needed) + " bytes), the file has " +
         std::to_string(b.size()));
  if (count == 0) fail("the file holds no point");

  double scale[3], add[3];
  for (int k = 0; k < 3; ++k) scale[k] = le<double>(b, 131 + 8 * k), add[k] = le<double>(b, 155 + 8 * k);
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(scale[k]) || scale[k] == 0 || !std::isfinite(add[k]))
      fail("header scale/offset of axis " + std::string(1, "XYZ"[k]) + " is zero or not finite");

  TerrainPoints pts;
  const size_t n = static_cast<size_t>(count);
  pts.positions.resize(n);
  pts.classes.resize(n);
  std::vector<std::array<std::uint16_t, 3>> rgb;
  if (layout.rgbOffset) rgb.resize(n);
  std::uint16_t maxChannel = 0;
  for (size_t i = 0; i < n; ++i) {
    const size_t at = offset + i * recordLength;
    const auto x = le<std::int32_t>(b, at), y = le<std::int32_t>(b, at + 4), z = le<std::int32_t>(b, at + 8);
    pts.positions[i] = Vec3(x * scale[0] + add[0], y * scale[1] + add[1], z * scale[2] + add[2]);
    // Formats 0-5 keep the class in the low 5 bits (the others are flags); 6-10 give it a byte.
    pts.classes[i] = layout.extended ? static_cast<unsigned char>(b[at + 16]) : (static_cast<unsigned char>(b[at + 15]) & 31);
    if (layout.rgbOffset) {
      for (int c = 0; c < 3; ++c) {
        rgb[i][c] = le<std::uint16_t>(b, at + layout.rgbOffset + 2 * c);
        maxChannel = std::max(maxChannel, rgb[i][c]);
      }
    }
  }
  if (layout.rgbOffset) {
    // The specification normalises colours to 16 bits, but many writers store 8-bit values in the
    // 16-bit fields; when nothing exceeds 255 the file is taken to be one of those.
    const double full = maxChannel <= 255 ? 255.0 : 65535.0;
    pts.colors.resize(n);
    for (size_t i = 0; i < n; ++i) pts.colors[i] = Eigen::Vector3d(rgb[i][0], rgb[i][1], rgb[i][2]) / full;
    if (full == 255.0) pts.notes.push_back("LAS colors are all <= 255: read as 8-bit values");
  }
  return pts;
}

}  // namespace geoshift

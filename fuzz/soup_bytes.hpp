#pragma once
// Fuzz bytes -> a triangle soup, for the mesh building and filter harnesses. The encoding makes
// the awkward cases cheap for the fuzzer to reach: shared and repeated indices, indices out of
// range (negative, past the end, INT_MIN/INT_MAX), coincident and collinear corners, NaN, infinities,
// huge and tiny coordinates.
//
//   byte 0          vertex count n (0..255)
//   3n coordinates  one byte each: 0..239 a grid value (b - 120) / 4; 240 NaN, 241 +inf, 242 -inf,
//                   243 1e308, 244 -1e308, 245 1e-310 (subnormal), 246 5e15 (ulp 1), 247 1e150,
//                   248..255 the next 8 bytes as a raw double
//   the rest        faces, three bytes each: a signed byte is an index, except -128 (INT_MIN),
//                   127 (INT_MAX) and 126 (n, one past the last vertex)
// Input that ends early ends the soup there (a partial face is dropped).
#include <climits>
#include <cstdint>
#include <cstring>
#include <limits>

#include "geoshift/mesh.hpp"

namespace geoshift::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, size_t size) : p_(data), end_(data + size) {}
  size_t left() const { return static_cast<size_t>(end_ - p_); }
  std::uint8_t byte() { return p_ < end_ ? *p_++ : 0; }
  double rawDouble() {
    double v = 0;
    std::uint8_t b[8] = {};
    for (std::uint8_t& x : b) x = byte();
    std::memcpy(&v, b, sizeof v);
    return v;
  }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

inline double coordinate(ByteReader& in) {
  const int b = in.byte();
  if (b < 240) return (b - 120) / 4.0;
  switch (b) {
    case 240: return std::numeric_limits<double>::quiet_NaN();
    case 241: return std::numeric_limits<double>::infinity();
    case 242: return -std::numeric_limits<double>::infinity();
    case 243: return 1e308;
    case 244: return -1e308;
    case 245: return 1e-310;
    case 246: return 5e15;
    case 247: return 1e150;
    default: return in.rawDouble();
  }
}

inline TriangleSoup soupFromBytes(const std::uint8_t* data, size_t size) {
  ByteReader in(data, size);
  TriangleSoup s;
  const int n = in.byte();
  for (int i = 0; i < n && in.left() > 0; ++i) {
    const double x = coordinate(in), y = coordinate(in), z = coordinate(in);
    s.positions.emplace_back(x, y, z);
  }
  auto index = [&](std::uint8_t b) {
    const auto v = static_cast<std::int8_t>(b);
    if (v == -128) return INT_MIN;
    if (v == 127) return INT_MAX;
    if (v == 126) return n;
    return static_cast<int>(v);
  };
  while (in.left() >= 3) {
    const std::uint8_t a = in.byte(), b = in.byte(), c = in.byte();
    s.faces.push_back({index(a), index(b), index(c)});
  }
  return s;
}

}  // namespace geoshift::fuzz

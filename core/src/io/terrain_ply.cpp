// PLY point sets (ascii, binary little/big endian): the vertex element's position, color and
// class. Other elements are skipped (lists included), so a PLY mesh reads as its vertices.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>

#include "geoshift/terrain.hpp"
#include "io_detail.hpp"

namespace geoshift {
namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

bool typeOf(const std::string& s, Type& t) {
  static const std::pair<const char*, Type> names[] = {
      {"char", Type::I8},    {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},
      {"short", Type::I16},  {"int16", Type::I16},   {"ushort", Type::U16}, {"uint16", Type::U16},
      {"int", Type::I32},    {"int32", Type::I32},   {"uint", Type::U32},   {"uint32", Type::U32},
      {"float", Type::F32},  {"float32", Type::F32}, {"double", Type::F64}, {"float64", Type::F64}};
  for (const auto& [name, type] : names)
    if (s == name) return t = type, true;
  return false;
}

size_t sizeOf(Type t) {
  switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    default: return 8;
  }
}

struct Property {
  std::string name;
  Type type = Type::F32;
  bool list = false;
  Type countType = Type::U8;
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> props;
};

class Body {
 public:
  Body(const std::string& path, const std::string& bytes, size_t pos, int format)
      : path_(path), b_(bytes), pos_(pos), format_(format) {}

  double read(Type t, const std::string& what) {
    if (format_ == 0) return readText(what);
    const size_t n = sizeOf(t);
    if (pos_ + n > b_.size()) io::fail(path_, "truncated: the data ends inside " + what);
    unsigned char raw[8];
    std::memcpy(raw, b_.data() + pos_, n);
    if (format_ == 2) std::reverse(raw, raw + n);
    pos_ += n;
    switch (t) {
      case Type::I8: return static_cast<signed char>(raw[0]);
      case Type::U8: return raw[0];
      case Type::I16: { std::int16_t v; std::memcpy(&v, raw, 2); return v; }
      case Type::U16: { std::uint16_t v; std::memcpy(&v, raw, 2); return v; }
      case Type::I32: { std::int32_t v; std::memcpy(&v, raw, 4); return v; }
      case Type::U32: { std::uint32_t v; std::memcpy(&v, raw, 4); return v; }
      case Type::F32: { float v; std::memcpy(&v, raw, 4); return v; }
      default: { double v; std::memcpy(&v, raw, 8); return v; }
    }
  }

 private:
  double readText(const std::string& what) {
    while (pos_ < b_.size() && std::isspace(static_cast<unsigned char>(b_[pos_]))) ++pos_;
    if (pos_ >= b_.size()) io::fail(path_, "truncated: the data ends before " + what);
    double v = 0;
    const auto r = std::from_chars(b_.data() + pos_, b_.data() + b_.size(), v);
    if (r.ec != std::errc()) io::fail(path_, "not a number at " + what);
    pos_ = static_cast<size_t>(r.ptr - b_.data());
    return v;
  }

  const std::string& path_;
  const std::string& b_;
  size_t pos_;
  int format_;  // 0 ascii, 1 binary little endian, 2 binary big endian
};

}  // namespace

TerrainPoints readPlyPoints(const std::string& path) {
  const std::string b = io::readWholeFile(path);
  auto fail = [&](const std::string& what) { io::fail(path, what); };
  if (b.compare(0, 3, "ply") != 0) fail("not a PLY file (no 'ply' magic)");
  const size_t end = b.find("end_header");
  if (end == std::string::npos) fail("PLY header has no end_header");
  size_t bodyStart = b.find('\n', end);
  bodyStart = bodyStart == std::string::npos ? b.size() : bodyStart + 1;

  std::istringstream header(b.substr(0, end));
  std::string line;
  int format = -1;
  std::vector<Element> elements;
  int lineNo = 0;
  while (std::getline(header, line)) {
    ++lineNo;
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    const std::string at = "header line " + std::to_string(lineNo);
    if (word == "format") {
      std::string f;
      ls >> f;
      if (f == "ascii") format = 0;
      else if (f == "binary_little_endian") format = 1;
      else if (f == "binary_big_endian") format = 2;
      else fail(at + ": unknown format '" + f + "'");
    } else if (word == "element") {
      Element e;
      long long count = -1;
      ls >> e.name >> count;
      if (!ls || count < 0) fail(at + ": malformed element line");
      e.count = static_cast<size_t>(count);
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) fail(at + ": property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.list = true;
        if (!typeOf(ct, p.countType) || !typeOf(it, p.type)) fail(at + ": unknown list types '" + ct + " " + it + "'");
      } else {
        ls >> p.name;
        if (!typeOf(t, p.type)) fail(at + ": unknown property type '" + t + "'");
      }
      elements.back().props.push_back(p);
    }
  }
  if (format < 0) fail("PLY header has no format line");

  TerrainPoints pts;
  Body body(path, b, bodyStart, format);
  for (const Element& e : elements) {
    if (e.name != "vertex") {
      for (size_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          const std::string what = "element '" + e.name + "' " + std::to_string(i);
          const double m = p.list ? body.read(p.countType, what) : 1;
          if (!(m >= 0)) fail(what + ": negative list length");
          for (double k = 0; k < m; ++k) body.read(p.type, what);
        }
      continue;
    }
    int ix = -1, iy = -1, iz = -1, ir = -1, ig = -1, ib = -1, ic = -1;
    for (size_t k = 0; k < e.props.size(); ++k) {
      const std::string& nm = e.props[k].name;
      const int kk = static_cast<int>(k);
      if (nm == "x") ix = kk;
      else if (nm == "y") iy = kk;
      else if (nm == "z") iz = kk;
      else if (nm == "red" || nm == "r" || nm == "diffuse_red") ir = kk;
      else if (nm == "green" || nm == "g" || nm == "diffuse_green") ig = kk;
      else if (nm == "blue" || nm == "b" || nm == "diffuse_blue") ib = kk;
      else if (nm == "classification" || nm == "class" || nm == "label" || nm == "scalar_Classification") ic = kk;
    }
    if (ix < 0 || iy < 0 || iz < 0) fail("the vertex element has no x, y and z properties");
    if (e.props[ix].list || e.props[iy].list || e.props[iz].list) fail("vertex x/y/z are lists");
    // Before allocating: every vertex takes at least its fixed-size properties (binary) or one
    // character and a separator per property (ascii) of what is left of the file.
    size_t minRecord = 0;
    for (const Property& p : e.props) minRecord += format == 0 ? 2 : (p.list ? sizeOf(p.countType) : sizeOf(p.type));
    if (minRecord > 0 && e.count > (b.size() - std::min(b.size(), bodyStart)) / minRecord)
      fail("truncated: the header announces " + std::to_string(e.count) + " vertices, more than the data can hold");
    const bool color = ir >= 0 && ig >= 0 && ib >= 0;
    const double colorScale = !color ? 1.0 : e.props[ir].type == Type::U8 ? 1.0 / 255 : e.props[ir].type == Type::U16 ? 1.0 / 65535 : 1.0;
    pts.positions.resize(e.count);
    if (ic >= 0) pts.classes.resize(e.count);
    if (color) pts.colors.resize(e.count);
    std::vector<double> row(e.props.size());
    for (size_t i = 0; i < e.count; ++i) {
      const std::string what = "vertex " + std::to_string(i);
      for (size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (p.list) {
          const double m = body.read(p.countType, what);
          for (double j = 0; j < m; ++j) body.read(p.type, what);
        } else {
          row[k] = body.read(p.type, what);
        }
      }
      pts.positions[i] = Vec3(row[ix], row[iy], row[iz]);
      if (!pts.positions[i].allFinite()) fail(what + " has a NaN or infinite coordinate");
      if (ic >= 0) pts.classes[i] = static_cast<int>(row[ic]);
      if (color) pts.colors[i] = (Eigen::Vector3d(row[ir], row[ig], row[ib]) * colorScale).cwiseMax(0.0).cwiseMin(1.0);
    }
    if (ic >= 0) pts.notes.push_back("classes from the PLY property '" + e.props[ic].name + "'");
    return pts;
  }
  io::fail(path, "the PLY file has no vertex element");
}

}  // namespace geoshift

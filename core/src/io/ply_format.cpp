// The PLY container: header, bounds of the declared counts, and record reading for ascii and
// binary files. See ply_format.hpp.
#include "ply_format.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "io_detail.hpp"

namespace geoshift::io::ply {
namespace {

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

bool inRange(double v, Type t) {
  switch (t) {
    case Type::I8: return v >= -128 && v <= 127;
    case Type::U8: return v >= 0 && v <= 255;
    case Type::I16: return v >= -32768 && v <= 32767;
    case Type::U16: return v >= 0 && v <= 65535;
    case Type::I32: return v >= -2147483648.0 && v <= 2147483647.0;
    case Type::U32: return v >= 0 && v <= 4294967295.0;
    default: return true;
  }
}

}  // namespace

size_t sizeOf(Type t) {
  switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    case Type::F64: return 8;
  }
  return 8;
}

bool isInteger(Type t) { return t != Type::F32 && t != Type::F64; }

const char* typeName(Type t) {
  switch (t) {
    case Type::I8: return "char";
    case Type::U8: return "uchar";
    case Type::I16: return "short";
    case Type::U16: return "ushort";
    case Type::I32: return "int";
    case Type::U32: return "uint";
    case Type::F32: return "float";
    case Type::F64: return "double";
  }
  return "?";
}

int Element::find(const std::string& property) const {
  for (size_t k = 0; k < props.size(); ++k)
    if (props[k].name == property) return static_cast<int>(k);
  return -1;
}

int Header::findElement(const std::string& name) const {
  for (size_t k = 0; k < elements.size(); ++k)
    if (elements[k].name == name) return static_cast<int>(k);
  return -1;
}

Header parseHeader(const std::string& path, const std::string& b) {
  if (b.compare(0, 3, "ply") != 0 || (b.size() > 3 && b[3] != '\n' && b[3] != '\r'))
    io::fail(path, "not a PLY file (the first line is not 'ply')");
  Header h;
  bool hasFormat = false, ended = false;
  size_t pos = 0, lineNo = 0;
  while (pos < b.size() && !ended) {
    size_t eol = b.find('\n', pos);
    const size_t next = eol == std::string::npos ? b.size() : eol + 1;
    if (eol == std::string::npos) eol = b.size();
    std::string line = b.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = next;
    ++lineNo;
    const std::string at = "header line " + std::to_string(lineNo);
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (lineNo == 1 || word.empty() || word == "comment" || word == "obj_info") continue;
    if (word == "end_header") {
      ended = true;
    } else if (word == "format") {
      std::string f, version;
      ls >> f >> version;
      if (f == "ascii") h.encoding = Encoding::Ascii;
      else if (f == "binary_little_endian") h.encoding = Encoding::BinaryLittleEndian;
      else if (f == "binary_big_endian") h.encoding = Encoding::BinaryBigEndian;
      else io::fail(path, at + ": unknown format '" + f + "'");
      if (version != "1.0") io::fail(path, at + ": unsupported PLY version '" + version + "' (1.0 expected)");
      hasFormat = true;
    } else if (word == "element") {
      Element e;
      std::string count;
      ls >> e.name >> count;
      unsigned long long n = 0;
      const auto r = std::from_chars(count.data(), count.data() + count.size(), n);
      if (e.name.empty() || count.empty() || r.ec != std::errc() || r.ptr != count.data() + count.size())
        io::fail(path, at + ": malformed element line '" + line + "' (expected: element NAME COUNT)");
      e.count = n;
      h.elements.push_back(e);
    } else if (word == "property") {
      if (h.elements.empty()) io::fail(path, at + ": property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.list = true;
        if (!typeOf(ct, p.countType)) io::fail(path, at + ": unknown list count type '" + ct + "'");
        if (!isInteger(p.countType)) io::fail(path, at + ": list count type '" + ct + "' is not an integer type");
        if (!typeOf(it, p.type)) io::fail(path, at + ": unknown list item type '" + it + "'");
      } else {
        ls >> p.name;
        if (!typeOf(t, p.type)) io::fail(path, at + ": unknown property type '" + t + "'");
      }
      if (p.name.empty()) io::fail(path, at + ": property without a name");
      if (h.elements.back().find(p.name) >= 0)
        io::fail(path, at + ": property '" + p.name + "' appears twice in element '" + h.elements.back().name + "'");
      h.elements.back().props.push_back(p);
    } else {
      io::fail(path, at + ": unknown header keyword '" + word + "'");
    }
  }
  if (!ended) io::fail(path, "the PLY header has no end_header line");
  if (!hasFormat) io::fail(path, "the PLY header has no format line");
  h.bodyStart = pos;
  h.bodyLine = lineNo + 1;

  // Before anything is allocated: the smallest record of each element (binary: its fixed-size
  // values and list counts; ascii: one digit and one separator per value) times its count must fit
  // in what is left of the file.
  size_t left = b.size() - h.bodyStart;
  for (const Element& e : h.elements) {
    size_t minRecord = 0;
    for (const Property& p : e.props)
      minRecord += h.encoding == Encoding::Ascii ? 2 : sizeOf(p.list ? p.countType : p.type);
    // Records without properties hold nothing, so no size bounds their count: a tiny file could
    // declare 10^12 of them and keep a reader looping. No writer has a use for them.
    if (minRecord == 0) {
      if (e.count > 0)
        io::fail(path, "element '" + e.name + "' declares " + std::to_string(e.count) +
                           " records but no properties");
      continue;
    }
    // The last ascii value may end the file without a separator.
    const size_t room = h.encoding == Encoding::Ascii ? left + 1 : left;
    if (e.count > room / minRecord)
      io::fail(path, "element '" + e.name + "' declares " + std::to_string(e.count) +
                         " records, more than the remaining " + std::to_string(left) +
                         " bytes of the file can hold (truncated file or wrong count)");
    left -= std::min(left, static_cast<size_t>(e.count) * minRecord);  // fits: checked above
  }
  return h;
}

Records::Records(const std::string& path, const std::string& bytes, const Header& header)
    : path_(path), b_(bytes), encoding_(header.encoding), pos_(header.bodyStart), line_(header.bodyLine - 1) {}

void Records::fail(const std::string& what) const {
  const std::string file = encoding_ == Encoding::Ascii ? path_ + ":" + std::to_string(line_) : path_;
  const std::string where = element_ ? element_->name + " " + std::to_string(index_) : std::string();
  io::fail(file, where + ": " + what);
}

void Records::begin(const Element& element, size_t index) {
  element_ = &element;
  index_ = index;
  if (encoding_ != Encoding::Ascii) return;
  tokens_.clear();
  next_ = 0;
  // One record per line; blank lines between records are tolerated.
  while (tokens_.empty()) {
    if (pos_ >= b_.size()) {
      ++line_;
      fail("truncated: the file ends before this record");
    }
    size_t eol = b_.find('\n', pos_);
    if (eol == std::string::npos) eol = b_.size();
    ++line_;
    for (size_t i = pos_; i < eol;) {
      while (i < eol && std::isspace(static_cast<unsigned char>(b_[i]))) ++i;
      const size_t s = i;
      while (i < eol && !std::isspace(static_cast<unsigned char>(b_[i]))) ++i;
      if (i > s) tokens_.emplace_back(s, i);
    }
    pos_ = eol < b_.size() ? eol + 1 : eol;
  }
}

void Records::end() {
  if (encoding_ == Encoding::Ascii && next_ < tokens_.size())
    fail(std::to_string(tokens_.size() - next_) + " more value(s) on the line than the header declares");
}

double Records::binary(Type t, const char* what, const std::string& name) {
  const size_t n = sizeOf(t);
  if (b_.size() - pos_ < n) fail(std::string("truncated: the file ends inside ") + what + " '" + name + "'");
  unsigned char raw[8];
  std::memcpy(raw, b_.data() + pos_, n);
  if (encoding_ == Encoding::BinaryBigEndian) std::reverse(raw, raw + n);
  pos_ += n;
  switch (t) {
    case Type::I8: return static_cast<signed char>(raw[0]);
    case Type::U8: return raw[0];
    case Type::I16: { std::int16_t v; std::memcpy(&v, raw, 2); return v; }
    case Type::U16: { std::uint16_t v; std::memcpy(&v, raw, 2); return v; }
    case Type::I32: { std::int32_t v; std::memcpy(&v, raw, 4); return v; }
    case Type::U32: { std::uint32_t v; std::memcpy(&v, raw, 4); return v; }
    case Type::F32: { float v; std::memcpy(&v, raw, 4); return v; }
    case Type::F64: { double v; std::memcpy(&v, raw, 8); return v; }
  }
  return 0;
}

double Records::text(Type t, const char* what, const std::string& name) {
  if (next_ >= tokens_.size()) fail(std::string("the line ends before ") + what + " '" + name + "'");
  const auto [s, e] = tokens_[next_++];
  const char* first = b_.data() + s;
  const char* last = b_.data() + e;
  const auto described = [&] { return std::string(" (") + what + " '" + name + "')"; };
  if (isInteger(t)) {
    long long v = 0;
    const auto r = std::from_chars(first, last, v);
    if (r.ec != std::errc() || r.ptr != last || !inRange(static_cast<double>(v), t))
      fail("'" + std::string(first, last) + "' is not a valid " + typeName(t) + described());
    return static_cast<double>(v);
  }
  double v = 0;
  if (!io::parseDouble(first, last, v)) fail("'" + std::string(first, last) + "' is not a number" + described());
  return v;
}

double Records::scalar(const Property& p) {
  return encoding_ == Encoding::Ascii ? text(p.type, "property", p.name) : binary(p.type, "property", p.name);
}

size_t Records::listLength(const Property& p) {
  const char* what = "the length of list";
  const double n = encoding_ == Encoding::Ascii ? text(p.countType, what, p.name) : binary(p.countType, what, p.name);
  if (n < 0) fail("list '" + p.name + "' has a negative length " + io::formatNumber(n));
  const size_t len = static_cast<size_t>(n);
  const size_t avail = encoding_ == Encoding::Ascii ? tokens_.size() - next_ : (b_.size() - pos_) / sizeOf(p.type);
  if (len > avail)
    fail("list '" + p.name + "' declares " + std::to_string(len) + " items, more than the " +
         (encoding_ == Encoding::Ascii ? "line" : "file") + " holds");
  return len;
}

double Records::listItem(const Property& p) {
  const char* what = "an item of list";
  return encoding_ == Encoding::Ascii ? text(p.type, what, p.name) : binary(p.type, what, p.name);
}

void Records::skip(const Property& p) {
  if (!p.list) {
    scalar(p);
    return;
  }
  const size_t n = listLength(p);
  for (size_t i = 0; i < n; ++i) listItem(p);
}

bool Records::trailingData() const {
  if (encoding_ != Encoding::Ascii) return pos_ < b_.size();
  for (size_t i = pos_; i < b_.size(); ++i)
    if (!std::isspace(static_cast<unsigned char>(b_[i])) && b_[i] != '\0') return true;
  return false;
}

}  // namespace geoshift::io::ply

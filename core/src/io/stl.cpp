// STL: ascii and binary, read into one part welded by exact position (STL repeats every corner in
// every triangle); written binary, world space, positions only.
#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

struct PositionHash {
  size_t operator()(const Vec3& p) const {
    size_t h = 1469598103934665603ull;
    for (int k = 0; k < 3; ++k) {
      uint64_t bits;
      std::memcpy(&bits, &p[k], 8);
      h = (h ^ bits) * 1099511628211ull;
      h ^= h >> 29;
    }
    return h;
  }
};

// Corners to welded vertices; messages name the triangle whose corner broke a rule.
class Welder {
 public:
  Welder(const std::string& path, MeshPart& part, size_t maxVertices)
      : path_(path), part_(part), max_(maxVertices) {}

  int add(Vec3 p, const std::string& where) {
    if (!p.allFinite()) fail(path_, where + " has a non-finite coordinate");
    for (int k = 0; k < 3; ++k)
      if (p[k] == 0) p[k] = 0;  // -0 and +0 are one position
    const auto [it, added] = index_.emplace(p, static_cast<int>(part_.positions.size()));
    if (added) {
      if (part_.positions.size() >= max_)
        fail(path_, where + ": more than " + std::to_string(max_) +
                        " distinct vertices (raise the limit with --max-vertices)");
      part_.positions.push_back(p);
    }
    return it->second;
  }

 private:
  const std::string& path_;
  MeshPart& part_;
  size_t max_;
  std::unordered_map<Vec3, int, PositionHash> index_;
};

template <class T>
T loadLittle(const char* p) {
  char raw[sizeof(T)];
  std::memcpy(raw, p, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
  T v;
  std::memcpy(&v, raw, sizeof(T));
  return v;
}

void readBinary(const std::string& path, const std::string& b, MeshPart& part, Welder& weld) {
  const uint32_t count = loadLittle<uint32_t>(b.data() + 80);
  part.faces.reserve(count);
  for (size_t t = 0; t < count; ++t) {
    const char* rec = b.data() + 84 + 50 * t;
    Face f;
    for (int k = 0; k < 3; ++k) {
      Vec3 p;
      for (int c = 0; c < 3; ++c) p[c] = loadLittle<float>(rec + 12 + 12 * k + 4 * c);
      f[k] = weld.add(p, "triangle " + std::to_string(t) + " vertex " + std::to_string(k));
    }
    part.faces.push_back(f);
  }
  (void)path;
}

// Whitespace-separated words with their line numbers, for the ascii grammar.
class Words {
 public:
  Words(const std::string& path, const std::string& b) : path_(path), b_(b) {}

  bool atEnd() {
    skipSpace();
    return pos_ >= b_.size();
  }
  std::string next(const std::string& expected) {
    skipSpace();
    if (pos_ >= b_.size()) fail(path_ + ":" + std::to_string(line_), "truncated: the file ends where " + expected + " was expected");
    const size_t s = pos_;
    while (pos_ < b_.size() && !std::isspace(static_cast<unsigned char>(b_[pos_]))) ++pos_;
    return b_.substr(s, pos_ - s);
  }
  void expect(const std::string& word, const std::string& context) {
    std::string w = next("'" + word + "'");
    std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return std::tolower(c); });
    if (w != word) err("expected '" + word + "' " + context + ", found '" + w.substr(0, 40) + "'");
  }
  double number(const std::string& what) {
    const std::string w = next(what);
    double v = 0;
    if (!io::parseDouble(w.data(), w.data() + w.size(), v)) err("'" + w.substr(0, 40) + "' is not a number (" + what + ")");
    return v;
  }
  void restOfLine() {
    while (pos_ < b_.size() && b_[pos_] != '\n') ++pos_;
  }
  [[noreturn]] void err(const std::string& what) const { fail(path_ + ":" + std::to_string(line_), what); }

 private:
  void skipSpace() {
    while (pos_ < b_.size() && std::isspace(static_cast<unsigned char>(b_[pos_]))) {
      if (b_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  const std::string& path_;
  const std::string& b_;
  size_t pos_ = 0;
  size_t line_ = 1;
};

void readAscii(const std::string& path, const std::string& b, MeshPart& part, Welder& weld) {
  Words w(path, b);
  size_t t = 0;
  while (!w.atEnd()) {
    w.expect("solid", "at the start of a solid");
    w.restOfLine();  // the solid's name
    for (;;) {
      std::string word = w.next("'facet' or 'endsolid'");
      std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
      if (word == "endsolid") {
        w.restOfLine();
        break;
      }
      const std::string tri = "triangle " + std::to_string(t);
      if (word != "facet") w.err("expected 'facet' or 'endsolid', found '" + word.substr(0, 40) + "'");
      w.expect("normal", "after 'facet' (" + tri + ")");
      for (int c = 0; c < 3; ++c) w.number(tri + " normal");
      w.expect("outer", "(" + tri + ")");
      w.expect("loop", "(" + tri + ")");
      Face f;
      for (int k = 0; k < 3; ++k) {
        const std::string corner = tri + " vertex " + std::to_string(k);
        w.expect("vertex", "(" + tri + " needs 3 vertices)");
        Vec3 p;
        for (int c = 0; c < 3; ++c) p[c] = w.number(corner);
        f[k] = weld.add(p, corner);
      }
      w.expect("endloop", "(" + tri + " has more than 3 vertices?)");
      w.expect("endfacet", "(" + tri + ")");
      part.faces.push_back(f);
      ++t;
    }
  }
}

// Binary files may begin with "solid" too; an ascii one continues with "facet" or "endsolid".
bool looksAscii(const std::string& b) {
  size_t s = b.find_first_not_of(" \t\r\n");
  if (s == std::string::npos || b.compare(s, 5, "solid") != 0) return false;
  const size_t eol = b.find('\n', s);
  if (eol == std::string::npos) return false;
  const size_t w = b.find_first_not_of(" \t\r\n", eol);
  return w != std::string::npos && (b.compare(w, 5, "facet") == 0 || b.compare(w, 8, "endsolid") == 0);
}

}  // namespace

Document readStl(const std::string& path, const ReadOptions& options) {
  const std::string b = readWholeFile(path);
  Document doc;
  doc.path = path;
  doc.format = FileFormat::Stl;
  MeshPart part;
  part.label = "STL";
  part.instances.push_back(Eigen::Matrix4d::Identity());
  Welder weld(path, part, options.maxVertices);
  const bool binarySize = b.size() >= 84 && b.size() == 84 + 50 * static_cast<size_t>(loadLittle<uint32_t>(b.data() + 80));
  if (binarySize) {
    readBinary(path, b, part, weld);
  } else if (looksAscii(b)) {
    readAscii(path, b, part, weld);
  } else if (b.size() < 84) {
    fail(path, "not an STL file: " + std::to_string(b.size()) +
                   " bytes, too short for a binary STL (84-byte header) and not ascii ('solid' ... 'facet')");
  } else {
    const uint32_t count = loadLittle<uint32_t>(b.data() + 80);
    fail(path, "binary STL header declares " + std::to_string(count) + " triangles, which need " +
                   std::to_string(84 + 50 * static_cast<uint64_t>(count)) + " bytes, but the file has " +
                   std::to_string(b.size()) + " (truncated or not an STL file)");
  }
  if (part.faces.empty()) fail(path, "the file contains no triangles");
  doc.parts.push_back(std::move(part));
  auto source = std::make_shared<DocumentSource>();
  source->format = FileFormat::Stl;
  doc.source = std::move(source);
  return doc;
}

std::vector<std::string> writeStl(const Document& document, const std::string& path) {
  std::vector<std::string> warnings;
  for (const auto& p : document.parts) {
    if (!p.normals.empty() || !p.colors.empty())
      warnings.push_back(path + ": STL stores positions only; vertex normals and colors are not written");
    for (const auto& e : p.extras)
      warnings.push_back(path + ": attribute '" + e.name + "' is not stored in STL");
    if (!warnings.empty()) break;
  }
  const TriangleSoup soup = worldSoup(document);
  if (soup.faces.size() > 0xffffffffull) fail(path, "too many triangles for a binary STL");
  std::string out(80, ' ');
  const char title[] = "binary STL written by geoshift";
  std::memcpy(out.data(), title, sizeof title - 1);
  out.reserve(84 + 50 * soup.faces.size());
  auto put = [&](auto v) {
    char raw[sizeof v];
    std::memcpy(raw, &v, sizeof v);
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof v);
    out.append(raw, sizeof v);
  };
  put(static_cast<uint32_t>(soup.faces.size()));
  for (const Face& f : soup.faces) {
    const Vec3 &a = soup.positions[f[0]], &b = soup.positions[f[1]], &c = soup.positions[f[2]];
    Vec3 n = (b - a).cross(c - a);
    if (n.norm() > 0) n.normalize();
    for (int k = 0; k < 3; ++k) put(static_cast<float>(n[k]));
    for (const Vec3* p : {&a, &b, &c})
      for (int k = 0; k < 3; ++k) put(static_cast<float>((*p)[k]));
    put(static_cast<uint16_t>(0));
  }
  AtomicFileSet files;
  files.add(path, std::move(out));
  files.commit();
  return warnings;
}

}  // namespace geoshift::io

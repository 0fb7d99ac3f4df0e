// OFF / COFF (Geomview object file format), read and written here: the format is small enough that
// a line-oriented parser gives better messages ("FILE:12: ...") than a generic tokenizer.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string_view>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

// The file is read once into memory and tokenized in place: a content line is a list of views into the
// text, so reading a large OFF costs little more than the file itself
// (docs/denoising.md#speed-and-memory).
struct Line {
  size_t number = 0;
  std::vector<std::string_view> tokens;
};

// The C locale's white space, without a call per character.
constexpr bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

class LineReader {
 public:
  explicit LineReader(const std::string& text) : text_(text) {}

  // The next line holding a token (comments from # to the end of the line and blank lines skipped);
  // false at the end of the text. `line` is reused so its token storage is allocated once.
  bool next(Line& line) {
    while (pos_ < text_.size()) {
      const size_t eol = std::min(text_.find('\n', pos_), text_.size());
      ++number_;
      line.number = number_;
      line.tokens.clear();
      size_t i = pos_;
      pos_ = eol + 1;
      while (i < eol) {
        const char c = text_[i];
        if (c == '#') break;
        if (isBlank(c)) {
          ++i;
          continue;
        }
        const size_t b = i;
        while (i < eol && text_[i] != '#' && !isBlank(text_[i])) ++i;
        line.tokens.emplace_back(text_.data() + b, i - b);
      }
      if (!line.tokens.empty()) return true;
    }
    return false;
  }

  // Content lines left from here on, counted without storing them.
  size_t remaining() const {
    LineReader copy = *this;
    Line scratch;
    size_t n = 0;
    while (copy.next(scratch)) ++n;
    return n;
  }

 private:
  const std::string& text_;
  size_t pos_ = 0;
  size_t number_ = 0;
};

std::string where(const std::string& path, const Line& l) { return path + ":" + std::to_string(l.number); }

// Tokens end at whitespace, '#' or the text's terminating NUL, so strtod/strtol stop at the token's end
// when the whole token is a number.
double number(const std::string& path, const Line& l, std::string_view tok, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(tok.data(), &end);
  if (tok.empty() || end != tok.data() + tok.size())
    fail(where(path, l), "'" + std::string(tok) + "' is not a number (" + what + ")");
  return v;
}

long integer(const std::string& path, const Line& l, std::string_view tok, const std::string& what) {
  char* end = nullptr;
  const long v = std::strtol(tok.data(), &end, 10);
  if (tok.empty() || end != tok.data() + tok.size())
    fail(where(path, l), "'" + std::string(tok) + "' is not an integer (" + what + ")");
  return v;
}

}  // namespace

Document readOff(const std::string& path, const ReadOptions& options) {
  const std::string text = readWholeFile(path);
  LineReader reader(text);
  Line header;
  if (!reader.next(header)) fail(path, "empty file");
  std::vector<std::string_view> counts = header.tokens;
  const std::string keyword(counts[0]);
  bool hasColor = false, hasNormal = false, hasTexture = false;
  Line countLine = header;
  if (keyword.size() >= 3 && keyword.compare(keyword.size() - 3, 3, "OFF") == 0) {
    std::string prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.rfind("ST", 0) == 0) hasTexture = true, prefix.erase(0, 2);
    if (!prefix.empty() && prefix[0] == 'C') hasColor = true, prefix.erase(0, 1);
    if (!prefix.empty() && prefix[0] == 'N') hasNormal = true, prefix.erase(0, 1);
    if (!prefix.empty()) fail(where(path, header), "unsupported OFF variant '" + keyword + "'");
    counts.erase(counts.begin());
    if (counts.empty()) {
      if (!reader.next(countLine)) fail(path, "expected vertex and face counts after the OFF header");
      counts = countLine.tokens;
    }
  }  // else some writers omit the keyword: the first line holds the counts
  if (counts.size() < 2) fail(where(path, countLine), "expected vertex and face counts");
  const long nv = integer(path, countLine, counts[0], "vertex count");
  const long nf = integer(path, countLine, counts[1], "face count");
  if (nv <= 0 || nf < 0)
    fail(where(path, countLine), "bad counts: " + std::to_string(nv) + " vertices, " + std::to_string(nf) + " faces");
  if (static_cast<unsigned long>(nv) > options.maxVertices)
    fail(where(path, countLine), "the header declares " + std::to_string(nv) + " vertices, more than the limit of " +
                                     std::to_string(options.maxVertices) + " (raise it with --max-vertices)");
  if (const size_t left = reader.remaining(); left < static_cast<size_t>(nv) + static_cast<size_t>(nf))
    fail(path, "expected " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                   " faces, the file has only " + std::to_string(left) + " data lines");

  Document doc;
  doc.path = path;
  doc.format = FileFormat::Off;
  MeshPart part;
  part.label = "OFF";
  part.instances.push_back(Eigen::Matrix4d::Identity());
  std::vector<Eigen::Vector4d> colors;
  bool floatColors = false;
  part.positions.reserve(static_cast<size_t>(nv));
  Line l;
  for (long v = 0; v < nv; ++v) {
    reader.next(l);
    const std::string what = "vertex " + std::to_string(v);
    if (l.tokens.size() < 3)
      fail(where(path, l), "expected 3 coordinates for " + what);
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = number(path, l, l.tokens[k], what);
    if (!p.allFinite()) fail(where(path, l), what + " has a non-finite coordinate");
    part.positions.push_back(p);
    size_t t = 3;
    if (hasNormal) {
      if (l.tokens.size() < t + 3) fail(where(path, l), "expected a normal for " + what);
      Vec3 n;
      for (int k = 0; k < 3; ++k) n[k] = number(path, l, l.tokens[t + k], what);
      part.normals.push_back(n);
      t += 3;
    }
    if (hasColor) {
      const size_t left = l.tokens.size() - t - (hasTexture ? 2 : 0);
      if (l.tokens.size() < t + 3 || (left != 3 && left != 4))
        fail(where(path, l), "expected a color (3 or 4 values) for " + what);
      Eigen::Vector4d c(0, 0, 0, -1);  // alpha -1: absent, opaque in the unit chosen below
      for (size_t k = 0; k < left; ++k) {
        const std::string_view tok = l.tokens[t + k];
        c[k] = number(path, l, tok, what);
        floatColors = floatColors || tok.find_first_of(".eE") != std::string_view::npos;
      }
      colors.push_back(c);
    }
  }
  // Integer colors are 0-255, decimal ones 0-1 (the two conventions found in COFF files).
  for (auto& c : colors) {
    if (!floatColors) c.head<3>() /= 255.0;
    c[3] = c[3] < 0 ? 1.0 : (floatColors ? c[3] : c[3] / 255.0);
  }
  part.colors = std::move(colors);

  bool faceColors = false;
  part.faces.reserve(static_cast<size_t>(nf));
  std::vector<int> idx;
  for (long f = 0; f < nf; ++f) {
    reader.next(l);
    const std::string what = "face " + std::to_string(f);
    const long n = integer(path, l, l.tokens[0], what + " vertex count");
    if (n < 3) fail(where(path, l), what + " has " + std::to_string(n) + " vertices (at least 3 needed)");
    if (l.tokens.size() < static_cast<size_t>(n) + 1)
      fail(where(path, l), "expected " + std::to_string(n) + " vertex indices for " + what);
    faceColors = faceColors || l.tokens.size() > static_cast<size_t>(n) + 1;
    idx.clear();
    for (long k = 0; k < n; ++k) {
      const long i = integer(path, l, l.tokens[1 + k], what);
      if (i < 0 || i >= nv)
        fail(where(path, l), what + " index " + std::to_string(i) +
                                                        " out of range (" + std::to_string(nv) + " vertices)");
      idx.push_back(static_cast<int>(i));
    }
    for (size_t k = 1; k + 1 < idx.size(); ++k) part.faces.push_back({idx[0], idx[k], idx[k + 1]});
  }
  if (faceColors) doc.warnings.push_back(path + ": face colors are ignored and not written back");
  if (part.faces.empty()) fail(path, "the file contains no triangles");
  doc.parts.push_back(std::move(part));
  auto source = std::make_shared<DocumentSource>();
  source->format = FileFormat::Off;
  doc.source = std::move(source);
  return doc;
}

std::vector<std::string> writeOff(const Document& document, const std::string& path) {
  std::vector<std::string> warnings;
  bool anyColor = false;
  for (const auto& p : document.parts) {
    anyColor = anyColor || !p.colors.empty();
    for (const auto& e : p.extras)
      warnings.push_back(path + ": extra attribute '" + e.name + "' is not stored in OFF");
  }
  // OFF holds one mesh: every part and instance in world space.
  const TriangleSoup soup = worldSoup(document);
  std::vector<Eigen::Vector4d> colors;
  if (anyColor) {
    static const std::vector<Eigen::Matrix4d> identity{Eigen::Matrix4d::Identity()};
    for (const auto& p : document.parts)
      for (size_t k = 0; k < (p.instances.empty() ? 1 : p.instances.size()); ++k)
        for (size_t v = 0; v < p.positions.size(); ++v)
          colors.push_back(p.colors.empty() ? Eigen::Vector4d(1, 1, 1, 1) : p.colors[v]);
  }
  std::ostringstream out;
  out << (anyColor ? "COFF\n" : "OFF\n");
  out << soup.positions.size() << " " << soup.faces.size() << " 0\n";
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    const auto& p = soup.positions[v];
    out << formatNumber(p.x()) << " " << formatNumber(p.y()) << " " << formatNumber(p.z());
    if (anyColor)
      for (int k = 0; k < 4; ++k) out << " " << static_cast<int>(std::lround(std::clamp(colors[v][k], 0.0, 1.0) * 255));
    out << "\n";
  }
  for (const auto& f : soup.faces) out << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  AtomicFileSet files;
  files.add(path, out.str());
  files.commit();
  return warnings;
}

}  // namespace geoshift::io

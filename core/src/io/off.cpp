// OFF / COFF (Geomview object file format), read and written here: the format is small enough that
// a line-oriented parser gives better messages ("FILE:12: ...") than a generic tokenizer.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

struct Line {
  size_t number = 0;
  std::vector<std::string> tokens;
};

// Content lines with their numbers; comments (# to end of line) and blank lines dropped.
std::vector<Line> contentLines(const std::string& text) {
  std::vector<Line> lines;
  std::istringstream in(text);
  size_t n = 0;
  for (std::string s; std::getline(in, s);) {
    ++n;
    if (const auto h = s.find('#'); h != std::string::npos) s.resize(h);
    std::istringstream ts(s);
    Line l{n, {}};
    for (std::string t; ts >> t;) l.tokens.push_back(t);
    if (!l.tokens.empty()) lines.push_back(std::move(l));
  }
  return lines;
}

double number(const std::string& path, const Line& l, const std::string& tok, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (tok.empty() || *end != '\0')
    fail(path + ":" + std::to_string(l.number), "'" + tok + "' is not a number (" + what + ")");
  return v;
}

long integer(const std::string& path, const Line& l, const std::string& tok, const std::string& what) {
  char* end = nullptr;
  const long v = std::strtol(tok.c_str(), &end, 10);
  if (tok.empty() || *end != '\0')
    fail(path + ":" + std::to_string(l.number), "'" + tok + "' is not an integer (" + what + ")");
  return v;
}

}  // namespace

Document readOff(const std::string& path, const ReadOptions& options) {
  const auto lines = contentLines(readWholeFile(path));
  if (lines.empty()) fail(path, "empty file");
  size_t li = 0;
  std::vector<std::string> counts = lines[0].tokens;
  const std::string keyword = counts[0];
  bool hasColor = false, hasNormal = false, hasTexture = false;
  if (keyword.size() >= 3 && keyword.compare(keyword.size() - 3, 3, "OFF") == 0) {
    std::string prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.rfind("ST", 0) == 0) hasTexture = true, prefix.erase(0, 2);
    if (!prefix.empty() && prefix[0] == 'C') hasColor = true, prefix.erase(0, 1);
    if (!prefix.empty() && prefix[0] == 'N') hasNormal = true, prefix.erase(0, 1);
    if (!prefix.empty())
      fail(path + ":" + std::to_string(lines[0].number), "unsupported OFF variant '" + keyword + "'");
    counts.erase(counts.begin());
    ++li;
    if (counts.empty()) {
      if (li >= lines.size()) fail(path, "expected vertex and face counts after the OFF header");
      counts = lines[li++].tokens;
    }
  } else {
    ++li;  // some writers omit the keyword: the first line holds the counts
  }
  const Line& countLine = lines[li - 1];
  if (counts.size() < 2)
    fail(path + ":" + std::to_string(countLine.number), "expected vertex and face counts");
  const long nv = integer(path, countLine, counts[0], "vertex count");
  const long nf = integer(path, countLine, counts[1], "face count");
  if (nv <= 0 || nf < 0)
    fail(path + ":" + std::to_string(countLine.number), "bad counts: " + std::to_string(nv) +
                                                            " vertices, " + std::to_string(nf) + " faces");
  if (static_cast<unsigned long>(nv) > options.maxVertices)
    fail(path + ":" + std::to_string(countLine.number),
         "the header declares " + std::to_string(nv) + " vertices, more than the limit of " +
             std::to_string(options.maxVertices) + " (raise it with --max-vertices)");
  if (lines.size() - li < static_cast<size_t>(nv) + static_cast<size_t>(nf))
    fail(path, "expected " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                   " faces, the file has only " + std::to_string(lines.size() - li) + " data lines");

  Document doc;
  doc.path = path;
  doc.format = FileFormat::Off;
  MeshPart part;
  part.label = "OFF";
  part.instances.push_back(Eigen::Matrix4d::Identity());
  std::vector<Eigen::Vector4d> colors;
  bool floatColors = false;
  for (long v = 0; v < nv; ++v) {
    const Line& l = lines[li++];
    const std::string what = "vertex " + std::to_string(v);
    if (l.tokens.size() < 3)
      fail(path + ":" + std::to_string(l.number), "expected 3 coordinates for " + what);
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = number(path, l, l.tokens[k], what);
    if (!p.allFinite()) fail(path + ":" + std::to_string(l.number), what + " has a non-finite coordinate");
    part.positions.push_back(p);
    size_t t = 3;
    if (hasNormal) {
      if (l.tokens.size() < t + 3) fail(path + ":" + std::to_string(l.number), "expected a normal for " + what);
      Vec3 n;
      for (int k = 0; k < 3; ++k) n[k] = number(path, l, l.tokens[t + k], what);
      part.normals.push_back(n);
      t += 3;
    }
    if (hasColor) {
      const size_t left = l.tokens.size() - t - (hasTexture ? 2 : 0);
      if (l.tokens.size() < t + 3 || (left != 3 && left != 4))
        fail(path + ":" + std::to_string(l.number), "expected a color (3 or 4 values) for " + what);
      Eigen::Vector4d c(0, 0, 0, -1);  // alpha -1: absent, opaque in the unit chosen below
      for (size_t k = 0; k < left; ++k) {
        const std::string& tok = l.tokens[t + k];
        c[k] = number(path, l, tok, what);
        floatColors = floatColors || tok.find_first_of(".eE") != std::string::npos;
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
  for (long f = 0; f < nf; ++f) {
    const Line& l = lines[li++];
    const std::string what = "face " + std::to_string(f);
    const long n = integer(path, l, l.tokens[0], what + " vertex count");
    if (n < 3) fail(path + ":" + std::to_string(l.number), what + " has " + std::to_string(n) + " vertices (at least 3 needed)");
    if (l.tokens.size() < static_cast<size_t>(n) + 1)
      fail(path + ":" + std::to_string(l.number), "expected " + std::to_string(n) + " vertex indices for " + what);
    faceColors = faceColors || l.tokens.size() > static_cast<size_t>(n) + 1;
    std::vector<int> idx;
    for (long k = 0; k < n; ++k) {
      const long i = integer(path, l, l.tokens[1 + k], what);
      if (i < 0 || i >= nv)
        fail(path + ":" + std::to_string(l.number), what + " index " + std::to_string(i) +
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

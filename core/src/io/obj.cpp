// OBJ through tinyobjloader for faces, normals and diagnostics; the `v` lines are also parsed here
// in double precision (tinyobjloader's float build would round them). On save the text (kept, or
// read again and checked) is scanned again and only its v, vn and f lines are rewritten, so groups,
// materials, texture coordinates and comments stay byte for byte (docs/io.md, OBJ).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string_view>

#include <tiny_obj_loader.h>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

// The numbers after the 'v' of a vertex line (text from just past the keyword to the line's end).
std::vector<double> vertexValues(std::string_view line, const std::string& path, size_t lineNo, size_t vertex) {
  std::vector<double> values;
  std::istringstream in{std::string(line)};
  for (std::string tok; in >> tok;) {
    char* stop = nullptr;
    const double v = std::strtod(tok.c_str(), &stop);
    if (*stop != '\0')
      fail(path + ":" + std::to_string(lineNo), "'" + tok + "' is not a number (vertex " + std::to_string(vertex) + ")");
    values.push_back(v);
  }
  return values;
}

// FNV-1a, 64 bits: tells whether a file read again for writing back is the one that was read.
std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

enum class LineKind { Vertex, Normal, Face, Other };

// Calls visit(kind, begin, end, lineNo) for every line of the text: begin is the offset of its
// keyword (its first character that is not a blank), end that of its terminator (or the end of the
// text). The one scanner of the reader and the writer, so that both see the same v, vn and f lines.
template <class Visit>
void forEachLine(std::string_view text, Visit&& visit) {
  size_t lineNo = 0;
  for (size_t pos = 0; pos < text.size();) {
    ++lineNo;
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    const size_t s = text.find_first_not_of(" \t", pos);
    const auto keyword = [&](std::string_view word) {
      return s < end && text.compare(s, word.size(), word) == 0 && s + word.size() < end &&
             (text[s + word.size()] == ' ' || text[s + word.size()] == '\t');
    };
    const LineKind kind = keyword("v")    ? LineKind::Vertex
                          : keyword("vn") ? LineKind::Normal
                          : keyword("f")  ? LineKind::Face
                                          : LineKind::Other;
    visit(kind, s, end, lineNo);
    pos = end;
    if (pos < text.size() && text[pos] == '\r') ++pos;
    if (pos < text.size() && text[pos] == '\n') ++pos;
  }
}

// The values of a vertex line (begin at its keyword), checked as the reader checks them.
std::vector<double> vertexLineValues(std::string_view text, size_t begin, size_t end, const std::string& path,
                                     size_t lineNo, size_t vertex) {
  std::vector<double> values = vertexValues(text.substr(begin + 1, end - begin - 1), path, lineNo, vertex);
  if (values.size() < 3)
    fail(path + ":" + std::to_string(lineNo), "expected 3 coordinates for vertex " + std::to_string(vertex));
  return values;
}

// The vertex lines' positions and colors (white where a line has none) into the part, and the
// number of v and vn lines into src.
void scanLines(const std::string& path, std::string_view text, ObjSource& src, std::vector<Vec3>& positions,
               std::vector<Vec3>& colors, bool& anyColor, bool& allColor) {
  forEachLine(text, [&](LineKind kind, size_t s, size_t end, size_t lineNo) {
    if (kind == LineKind::Normal) ++src.normalLineCount;
    if (kind != LineKind::Vertex) return;
    const size_t vi = ++src.vertexCount;  // OBJ numbers vertices from 1
    const std::vector<double> values = vertexLineValues(text, s, end, path, lineNo, vi);
    const Vec3 position(values[0], values[1], values[2]);
    if (!position.allFinite())
      fail(path + ":" + std::to_string(lineNo), "vertex " + std::to_string(vi) + " has a non-finite coordinate");
    const bool hasColor = values.size() >= 6;
    // Colors only once a line has one (white for the lines before it): most scans have none.
    if (hasColor && !anyColor) {
      colors.reserve(positions.capacity());
      colors.assign(positions.size(), Vec3::Ones());
    }
    anyColor = anyColor || hasColor;
    allColor = allColor && hasColor;
    positions.push_back(position);
    if (anyColor) colors.push_back(hasColor ? Vec3(values[3], values[4], values[5]) : Vec3::Ones());
  });
}

std::string vertexLine(const Vec3& p, const Eigen::Vector4d* color) {
  std::string s = "v " + formatNumber(p.x()) + " " + formatNumber(p.y()) + " " + formatNumber(p.z());
  if (color)
    for (int k = 0; k < 3; ++k) {
      s += ' ';
      s += formatNumber((*color)[k]);
    }
  return s;
}

}  // namespace

Document readObj(const std::string& path, const ReadOptions& options) {
  auto source = std::make_shared<DocumentSource>();
  source->format = FileFormat::Obj;
  ObjSource& src = source->obj;
  src.path = path;
  src.text = readWholeFile(path);
  // NUL never occurs in OBJ text; tinyobjloader would read binary data as lines of nothing.
  if (src.text.find('\0') != std::string::npos)
    fail(path, "not a text OBJ file: it holds NUL bytes (binary data)");
  src.size = src.text.size();
  if (!options.keepSourceText) src.hash = fnv1a(src.text);

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = true;
  config.mtl_search_path = std::filesystem::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  const bool ok = reader.ParseFromFile(path, config);
  Document doc;
  doc.path = path;
  doc.format = FileFormat::Obj;
  {
    std::istringstream ws(reader.Warning());
    for (std::string line; std::getline(ws, line);)
      if (!line.empty()) doc.warnings.push_back(path + ": " + line);
  }
  if (!ok) {
    std::string err = reader.Error();
    while (!err.empty() && err.back() == '\n') err.pop_back();
    fail(path, "cannot read OBJ: " + err);
  }
  MeshPart part;
  // As many as tinyobjloader found (checked against the v lines below): exactly sized, not doubled.
  part.positions.reserve(reader.GetAttrib().vertices.size() / 3);
  std::vector<Vec3> colors;
  bool anyColor = false, allColor = true;
  scanLines(path, src.text, src, part.positions, colors, anyColor, allColor);
  if (!options.keepSourceText) {
    src.textKept = false;
    std::string().swap(src.text);
  }
  if (src.vertexCount > options.maxVertices)
    fail(path, "the file has " + std::to_string(src.vertexCount) + " vertices, more than the limit of " +
                   std::to_string(options.maxVertices) + " (raise it with --max-vertices)");
  const auto& attrib = reader.GetAttrib();
  const size_t nv = src.vertexCount;
  if (attrib.vertices.size() / 3 != nv)
    fail(path, "found " + std::to_string(nv) + " 'v' lines but tinyobjloader read " +
                   std::to_string(attrib.vertices.size() / 3) + " vertices (line continuations are not supported)");

  part.label = std::filesystem::path(path).filename().string();
  part.instances.push_back(Eigen::Matrix4d::Identity());
  if (anyColor) {
    if (!allColor) doc.warnings.push_back(path + ": some vertices have no color; white used for them");
    part.colors.reserve(colors.size());
    for (const Vec3& c : colors) part.colors.emplace_back(c.x(), c.y(), c.z(), 1.0);
  }

  // OBJ indexes normals separately; a per-vertex normal exists only if every vertex has exactly one.
  std::vector<int> normalOf(nv, -2);
  bool consistent = !attrib.normals.empty();
  size_t faceNo = 0, triangles = 0;
  for (const auto& shape : reader.GetShapes())
    triangles += static_cast<size_t>(std::count(shape.mesh.num_face_vertices.begin(), shape.mesh.num_face_vertices.end(), 3u));
  part.faces.reserve(triangles);  // exactly sized, not doubled: held through the whole command
  for (const auto& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (const auto fv : shape.mesh.num_face_vertices) {
      ++faceNo;
      Face f{};
      for (size_t k = 0; k < fv; ++k) {
        const auto& idx = shape.mesh.indices[offset + k];
        // tinyobjloader turns a relative index (-k: the k-th vertex back) into an absolute one;
        // a negative result means it reached back past the first vertex.
        if (idx.vertex_index < 0)
          fail(path, "face " + std::to_string(faceNo) + " (group '" + shape.name +
                         "') has a relative vertex index that reaches back past the first vertex");
        if (static_cast<size_t>(idx.vertex_index) >= nv)
          fail(path, "face " + std::to_string(faceNo) + " (group '" + shape.name + "') references vertex " +
                         std::to_string(idx.vertex_index + 1) + " but the file has " + std::to_string(nv) +
                         " vertices");
        // tinyobjloader does not check vn / vt references against the lines that exist.
        const size_t nn = attrib.normals.size() / 3, nt = attrib.texcoords.size() / 2;
        if (idx.normal_index >= 0 && static_cast<size_t>(idx.normal_index) >= nn)
          fail(path, "face " + std::to_string(faceNo) + " (group '" + shape.name + "') references normal " +
                         std::to_string(idx.normal_index + 1) + " but the file has " + std::to_string(nn) + " normals");
        if (idx.texcoord_index >= 0 && static_cast<size_t>(idx.texcoord_index) >= nt)
          fail(path, "face " + std::to_string(faceNo) + " (group '" + shape.name + "') references texture coordinate " +
                         std::to_string(idx.texcoord_index + 1) + " but the file has " + std::to_string(nt));
        if (k < 3) f[k] = idx.vertex_index;
        int& n = normalOf[idx.vertex_index];
        if (n == -2) n = idx.normal_index;
        else if (n != idx.normal_index) consistent = false;
        if (idx.normal_index < 0) consistent = false;
      }
      if (fv == 3) part.faces.push_back(f);
      offset += fv;
    }
  }
  if (part.faces.empty()) fail(path, "the file contains no triangles");
  for (int n : normalOf) consistent = consistent && n >= 0;
  if (consistent) {
    for (int n : normalOf)
      part.normals.emplace_back(attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]);
    src.normals = part.normals;
    // The vn lines found must be tinyobjloader's normals one for one to be rewritten in place.
    if (src.normalLineCount == attrib.normals.size() / 3) src.normalOf = normalOf;
  }
  doc.parts.push_back(std::move(part));
  doc.source = std::move(source);
  return doc;
}

namespace {

std::string normalLine(const Vec3& n) {
  return "vn " + formatNumber(n.x()) + " " + formatNumber(n.y()) + " " + formatNumber(n.z());
}

// A face line without its normal references: "f 1/4/2 2//3 3" -> "f 1/4 2 3".
std::string withoutNormals(std::string_view line) {
  std::istringstream tokens{std::string(line)};
  std::string out, token;
  tokens >> out;  // "f"
  while (tokens >> token) {
    const size_t first = token.find('/');
    const size_t second = first == std::string::npos ? std::string::npos : token.find('/', first + 1);
    if (second != std::string::npos) token.erase(second);             // v/t/n -> v/t, v//n -> v/
    if (!token.empty() && token.back() == '/') token.pop_back();     // v/ -> v
    out += " " + token;
  }
  return out;
}

// What becomes of the file's vn lines: rewritten in place when every vertex sharing one has the
// same new normal (newNormal[j] for vn line j, null where it keeps its text); otherwise (a vn line
// shared across a crease the result no longer has, or vn lines that cannot be told apart) dropped,
// and the faces lose their normal references, so that viewers compute normals from the written
// positions.
struct NormalPlan {
  bool drop = false;
  std::vector<const Vec3*> newNormal;
};

NormalPlan normalPlan(const ObjSource& src, const MeshPart& part, const std::string& path,
                      std::vector<std::string>& warnings) {
  NormalPlan plan;
  std::vector<const Vec3*> normalOfLine(src.normalLineCount, nullptr);
  bool inPlace = src.normalOf.size() == part.normals.size();
  for (size_t v = 0; inPlace && v < part.normals.size(); ++v) {
    const int j = src.normalOf[v];
    inPlace = j >= 0 && static_cast<size_t>(j) < normalOfLine.size();
    if (!inPlace) break;
    if (!normalOfLine[j]) normalOfLine[j] = &part.normals[v];
    inPlace = *normalOfLine[j] == part.normals[v];
  }
  if (inPlace) {
    plan.newNormal.assign(src.normalLineCount, nullptr);
    for (size_t v = 0; v < part.normals.size(); ++v) {
      const int j = src.normalOf[v];
      if (normalOfLine[j] == &part.normals[v] && part.normals[v] != src.normals[v]) plan.newNormal[j] = &part.normals[v];
    }
    return plan;
  }
  warnings.push_back(path + ": the result's normals differ where vertices share a vn line; the vn lines are left out "
                            "(viewers compute normals from the positions)");
  plan.drop = true;
  return plan;
}

// The source's text for writing back into it: the text kept, or the file read again, which must
// be the one that was read (docs/io.md, OBJ).
const std::string& sourceText(const ObjSource& src, const std::string& out, std::string& again) {
  if (src.textKept) return src.text;
  const std::string hint = "; nothing written to " + out +
                           " (an OBJ is written back into its source's text, read again now; write another format, "
                           "e.g. .ply or .glb, or read the file again)";
  // The size first: a file that grew is not read whole to find that out.
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(src.path, ec);
  const std::uintmax_t size = regular ? std::filesystem::file_size(src.path, ec) : 0;
  if (!regular || ec) fail(src.path, "gone or unreadable since it was read" + hint);
  if (size != src.size) fail(src.path, "changed since it was read" + hint);
  try {
    again = readWholeFile(src.path);
  } catch (const InputError&) {
    fail(src.path, "gone or unreadable since it was read" + hint);
  }
  if (again.size() != src.size || fnv1a(again) != src.hash) fail(src.path, "changed since it was read" + hint);
  return again;
}

}  // namespace

std::vector<std::string> writeObjInto(const Document& document, const std::string& path) {
  const ObjSource& src = document.source->obj;
  if (document.parts.size() != 1) fail(path, "an OBJ document has exactly one part");
  const MeshPart& part = document.parts[0];
  if (part.positions.size() != src.vertexCount)
    fail(path, std::to_string(part.positions.size()) + " positions, the file has " +
                   std::to_string(src.vertexCount) + "; the vertex layout cannot change when writing back");
  std::vector<std::string> warnings;
  for (const auto& e : part.extras)
    warnings.push_back(path + ": extra attribute '" + e.name + "' is not stored in OBJ");
  NormalPlan normals;
  if (!part.normals.empty() && part.normals != src.normals) normals = normalPlan(src, part, path, warnings);

  std::string again;
  const std::string& text = sourceText(src, path, again);
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  size_t copied = 0;
  // The line [begin, end) becomes `with`; a removed line takes its line break with it.
  const auto replace = [&](size_t begin, size_t end, std::string_view with) {
    out.append(text, copied, begin - copied);
    out += with;
    copied = end;
    if (with.empty() && copied < text.size() && text[copied] == '\r') ++copied;
    if (with.empty() && copied < text.size() && text[copied] == '\n') ++copied;
  };
  size_t vertex = 0, normal = 0;
  forEachLine(text, [&](LineKind kind, size_t s, size_t end, size_t lineNo) {
    switch (kind) {
      case LineKind::Vertex: {
        const size_t i = vertex++;
        if (i >= part.positions.size()) fail(src.path, "changed since it was read; nothing written to " + path);
        const Eigen::Vector4d* color = part.colors.empty() ? nullptr : &part.colors[i];
        // Unchanged vertices keep their text, so a round trip without changes is byte-identical.
        const std::vector<double> was = vertexLineValues(text, s, end, src.path, lineNo, i + 1);
        const bool hadColor = was.size() >= 6;
        const bool samePosition = part.positions[i] == Vec3(was[0], was[1], was[2]);
        const bool sameColor = color ? (hadColor && color->head<3>() == Vec3(was[3], was[4], was[5])) : !hadColor;
        if (!samePosition || !sameColor) replace(s, end, vertexLine(part.positions[i], color));
        return;
      }
      case LineKind::Normal: {
        const size_t j = normal++;
        if (normals.drop) replace(s, end, "");
        else if (j < normals.newNormal.size() && normals.newNormal[j]) replace(s, end, normalLine(*normals.newNormal[j]));
        return;
      }
      case LineKind::Face:
        // Without vn lines a face has no normal references to lose: its text stays as it is.
        if (normals.drop && src.normalLineCount > 0) replace(s, end, withoutNormals(std::string_view(text).substr(s, end - s)));
        return;
      case LineKind::Other: return;
    }
  });
  out.append(text, copied, std::string::npos);
  AtomicFileSet files;
  files.add(path, std::move(out));
  files.commit();
  return warnings;
}

std::vector<std::string> writeObjFresh(const Document& document, const std::string& path) {
  std::vector<std::string> warnings;
  std::ostringstream out;
  out << "# written by geoshift\n";
  bool allNormals = true;
  for (const auto& p : document.parts) allNormals = allNormals && !p.normals.empty();
  size_t base = 0;
  static const std::vector<Eigen::Matrix4d> identity{Eigen::Matrix4d::Identity()};
  for (size_t i = 0; i < document.parts.size(); ++i) {
    const MeshPart& part = document.parts[i];
    for (const auto& e : part.extras)
      warnings.push_back(path + ": extra attribute '" + e.name + "' is not stored in OBJ");
    const auto& instances = part.instances.empty() ? identity : part.instances;
    for (size_t k = 0; k < instances.size(); ++k) {
      const Eigen::Matrix4d& m = instances[k];
      const Eigen::Matrix3d normalMatrix = m.topLeftCorner<3, 3>().inverse().transpose();
      const bool mirrored = m.topLeftCorner<3, 3>().determinant() < 0;
      out << "g part" << i;
      if (instances.size() > 1) out << "_" << k;
      out << "\n";
      for (size_t v = 0; v < part.positions.size(); ++v) {
        const Vec3 p = (m * part.positions[v].homogeneous()).hnormalized();
        out << vertexLine(p, part.colors.empty() ? nullptr : &part.colors[v]) << "\n";
      }
      if (allNormals)
        for (const auto& n : part.normals) {
          const Vec3 t = (normalMatrix * n).normalized();
          out << "vn " << formatNumber(t.x()) << " " << formatNumber(t.y()) << " " << formatNumber(t.z()) << "\n";
        }
      for (auto f : part.faces) {
        if (mirrored) std::swap(f[1], f[2]);
        out << "f";
        for (int c : f) {
          out << " " << base + c + 1;
          if (allNormals) out << "//" << base + c + 1;
        }
        out << "\n";
      }
      base += part.positions.size();
    }
  }
  AtomicFileSet files;
  files.add(path, out.str());
  files.commit();
  return warnings;
}

}  // namespace geoshift::io

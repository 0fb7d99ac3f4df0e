// PLY meshes: the vertex element (x y z, nx ny nz, red green blue alpha, any other scalar as a
// named attribute) and the face element's index lists, fan-triangulated. Written binary little
// endian with float or double values, whichever keeps every value exactly.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "io_detail.hpp"
#include "ply_format.hpp"

namespace geoshift::io {
namespace {

using namespace ply;

bool isColorType(Type t) { return t == Type::U8 || t == Type::U16 || t == Type::F32 || t == Type::F64; }

double colorScale(Type t) { return t == Type::U8 ? 1.0 / 255 : t == Type::U16 ? 1.0 / 65535 : 1.0; }

const char* const kReserved[] = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "alpha"};

bool reserved(const std::string& name) {
  for (const char* r : kReserved)
    if (name == r) return true;
  return false;
}


// What each vertex property becomes.
enum Role { Skip, Position, Normal, Color, Extra };

struct VertexLayout {
  std::vector<std::pair<Role, int>> role;  // per property: its role and channel (or extra's index)
  bool normals = false, colors = false;
};

// The vertex element's properties as positions, normals, colors and extra attributes (added to
// part.extras, named "_" + the property's name); InputError when x, y, z or a whole set is missing.
VertexLayout vertexLayout(const std::string& path, const Element& ve, MeshPart& part, std::vector<std::string>& warnings) {
  VertexLayout layout;
  layout.role.assign(ve.props.size(), {Skip, 0});
  int nNormal = 0, nColor = 0;
  bool alpha = false;
  for (size_t k = 0; k < ve.props.size(); ++k) {
    const Property& p = ve.props[k];
    if (p.list) {
      warnings.push_back(path + ": vertex list property '" + p.name + "' is ignored and not written back");
      continue;
    }
    static const char* const pos[] = {"x", "y", "z"};
    static const char* const nor[] = {"nx", "ny", "nz"};
    static const char* const col[] = {"red", "green", "blue", "alpha"};
    auto& role = layout.role[k];
    for (int c = 0; c < 3; ++c) {
      if (p.name == pos[c]) role = {Position, c};
      if (p.name == nor[c]) role = {Normal, c}, ++nNormal;
    }
    for (int c = 0; c < 4; ++c)
      if (p.name == col[c]) {
        if (!isColorType(p.type))
          fail(path, "vertex property '" + p.name + "' has type " + typeName(p.type) +
                         "; colors must be uchar, ushort, float or double");
        role = {Color, c};
        ++nColor;
        alpha = alpha || c == 3;
      }
    if (role.first == Skip) {
      role = {Extra, static_cast<int>(part.extras.size())};
      part.extras.push_back({"_" + p.name, 1, {}});
    }
  }
  for (const char* c : {"x", "y", "z"})
    if (ve.find(c) < 0 || ve.props[ve.find(c)].list)
      fail(path, std::string("the vertex element has no scalar property '") + c + "'");
  if (nNormal != 0 && nNormal != 3) fail(path, "the vertex element has some but not all of nx, ny, nz");
  if (nColor != 0 && nColor - (alpha ? 1 : 0) != 3) fail(path, "the vertex element has some but not all of red, green, blue");
  layout.normals = nNormal > 0;
  layout.colors = nColor > 0;
  return layout;
}

// The face element's index list property, -1 without a face element; the other properties and
// elements are reported as ignored.
int faceIndexProperty(const std::string& path, const Header& h, std::vector<std::string>& warnings) {
  const int fi = h.findElement("face");
  int indexProp = -1;
  if (fi >= 0) {
    const Element& fe = h.elements[fi];
    for (const char* name : {"vertex_indices", "vertex_index"})
      if (indexProp < 0) indexProp = fe.find(name);
    if (indexProp < 0) fail(path, "the face element has no 'vertex_indices' (or 'vertex_index') list");
    const Property& ip = fe.props[indexProp];
    if (!ip.list) fail(path, "face property '" + ip.name + "' is not a list");
    if (!isInteger(ip.type))
      fail(path, "face property '" + ip.name + "' has item type " + typeName(ip.type) + "; indices must be integers");
    for (size_t k = 0; k < fe.props.size(); ++k)
      if (static_cast<int>(k) != indexProp)
        warnings.push_back(path + ": face property '" + fe.props[k].name + "' is ignored and not written back");
  }
  for (const Element& e : h.elements)
    if (e.name != "vertex" && e.name != "face")
      warnings.push_back(path + ": element '" + e.name + "' (" + std::to_string(e.count) + ") is ignored and not written back");
  return indexProp;
}

void readVertexRecords(Records& rec, const Element& e, const VertexLayout& layout, MeshPart& part) {
  for (size_t i = 0; i < e.count; ++i) {
    rec.begin(e, i);
    for (size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (p.list) {
        rec.skip(p);
        continue;
      }
      const double v = rec.scalar(p);
      const auto [r, c] = layout.role[k];
      if (r == Position) part.positions[i][c] = v;
      else if (r == Normal) part.normals[i][c] = v;
      else if (r == Color) part.colors[i][c] = v * colorScale(p.type);
      else if (r == Extra) part.extras[c].values[i] = v;
    }
    rec.end();
    if (!part.positions[i].allFinite()) rec.fail("non-finite position");
  }
}

// Fan-triangulates every face; returns how many had more than 3 vertices.
size_t readFaceRecords(Records& rec, const Element& e, int indexProp, MeshPart& part) {
  const size_t nv = part.positions.size();
  size_t polygons = 0;
  std::vector<int> idx;
  part.faces.reserve(e.count);
  for (size_t i = 0; i < e.count; ++i) {
    rec.begin(e, i);
    for (size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (static_cast<int>(k) != indexProp) {
        rec.skip(p);
        continue;
      }
      const size_t n = rec.listLength(p);
      if (n < 3) rec.fail("a face needs at least 3 vertices, this one has " + std::to_string(n));
      idx.clear();
      for (size_t j = 0; j < n; ++j) {
        const double v = rec.listItem(p);
        if (v < 0 || v >= static_cast<double>(nv))
          rec.fail("index " + formatNumber(v) + " out of range (" + std::to_string(nv) + " vertices)");
        idx.push_back(static_cast<int>(v));
      }
      if (n > 3) ++polygons;
      for (size_t j = 1; j + 1 < n; ++j) part.faces.push_back({idx[0], idx[j], idx[j + 1]});
    }
    rec.end();
  }
  return polygons;
}

}  // namespace

Document readPly(const std::string& path, const ReadOptions& options) {
  const std::string b = readWholeFile(path);
  const Header h = parseHeader(path, b);
  const int vi = h.findElement("vertex");
  if (vi < 0) fail(path, "the PLY file has no vertex element");
  const Element& ve = h.elements[vi];
  if (ve.count > options.maxVertices)
    fail(path, "element 'vertex' declares " + std::to_string(ve.count) + " vertices, more than the limit of " +
                   std::to_string(options.maxVertices) + " (raise it with --max-vertices)");

  Document doc;
  doc.path = path;
  doc.format = FileFormat::Ply;
  MeshPart part;
  part.label = "PLY";
  part.instances.push_back(Eigen::Matrix4d::Identity());
  const VertexLayout layout = vertexLayout(path, ve, part, doc.warnings);
  const int fi = h.findElement("face");
  const int indexProp = faceIndexProperty(path, h, doc.warnings);

  // parseHeader checked every count against the file's size: these allocations are bounded by it.
  const size_t nv = ve.count;
  part.positions.resize(nv);
  if (layout.normals) part.normals.resize(nv);
  if (layout.colors) part.colors.assign(nv, Eigen::Vector4d(0, 0, 0, 1));
  for (auto& e : part.extras) e.values.resize(nv);

  Records rec(path, b, h);
  size_t polygons = 0;
  for (size_t ei = 0; ei < h.elements.size(); ++ei) {
    const Element& e = h.elements[ei];
    if (e.props.empty()) continue;
    if (static_cast<int>(ei) == vi) {
      readVertexRecords(rec, e, layout, part);
    } else if (static_cast<int>(ei) == fi) {
      polygons += readFaceRecords(rec, e, indexProp, part);
    } else {
      for (size_t i = 0; i < e.count; ++i) {
        rec.begin(e, i);
        for (const Property& p : e.props) rec.skip(p);
        rec.end();
      }
    }
  }
  if (rec.trailingData()) doc.warnings.push_back(path + ": data after the last element is ignored");
  if (polygons)
    doc.warnings.push_back(path + ": " + std::to_string(polygons) +
                           " polygons with more than 3 vertices were fan-triangulated (written back as triangles)");
  if (part.faces.empty()) fail(path, "the file contains no triangles");
  doc.parts.push_back(std::move(part));
  auto source = std::make_shared<DocumentSource>();
  source->format = FileFormat::Ply;
  doc.source = std::move(source);
  return doc;
}

namespace {

// Binary little endian output whatever the host's byte order.
class LittleEndian {
 public:
  explicit LittleEndian(std::string& out) : out_(out) {}
  template <class T>
  void put(T v) {
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
    out_.append(raw, sizeof(T));
  }

 private:
  std::string& out_;
};

bool allFloat(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) {
    return std::isnan(v) || static_cast<double>(static_cast<float>(v)) == v;
  });
}

bool allBytes(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) {
    const double s = v * 255;
    return s >= 0 && s <= 255 && std::abs(s - std::round(s)) < 1e-9;
  });
}

// One channel of the output: its PLY name and type, and every vertex's value.
struct Column {
  std::string name;
  std::vector<double> values;
  bool bytes = false;  // uchar color
  bool single = true;  // float rather than double
};

// Attributes every part has, with the same dimension; the others are reported as not written.
std::vector<std::pair<std::string, int>> sharedExtras(const Document& document, const std::string& path,
                                                      std::vector<std::string>& warnings) {
  std::vector<std::pair<std::string, int>> extras;
  for (const auto& e : document.parts.front().extras) {
    bool everywhere = true;
    for (const auto& p : document.parts)
      everywhere = everywhere && std::any_of(p.extras.begin(), p.extras.end(), [&](const ExtraAttribute& x) {
                     return x.name == e.name && x.dim == e.dim;
                   });
    if (everywhere) extras.emplace_back(e.name, e.dim);
  }
  for (const auto& p : document.parts)
    for (const auto& e : p.extras)
      if (std::none_of(extras.begin(), extras.end(), [&](const auto& x) { return x.first == e.name; }))
        warnings.push_back(path + ": attribute '" + e.name + "' not written: not every part has it");
  return extras;
}

// The vertex element's columns, world space, every instance of every part in turn: x y z, then nx
// ny nz (when every part has normals; unit length after the instance's normal matrix), the colors
// [colorBegin, colorEnd), then the shared attributes without their leading '_'.
class VertexColumns {
 public:
  VertexColumns(const Document& document, const std::string& path, std::vector<std::string>& warnings)
      : document_(document), path_(path), warnings_(warnings) {}

  std::vector<Column> columns;
  size_t colorBegin = 0, colorEnd = 0;

  void add(const TriangleSoup& soup) {
    bool allNormals = true, anyNormals = false, anyColor = false, anyAlpha = false;
    for (const auto& p : document_.parts) {
      allNormals = allNormals && !p.normals.empty();
      anyNormals = anyNormals || !p.normals.empty();
      anyColor = anyColor || !p.colors.empty();
      for (const auto& c : p.colors) anyAlpha = anyAlpha || c[3] != 1.0;
    }
    if (anyNormals && !allNormals) warnings_.push_back(path_ + ": normals not written: not every part has them");
    const std::vector<std::pair<std::string, int>> extras = sharedExtras(document_, path_, warnings_);
    for (int c = 0; c < 3; ++c) {
      columns.push_back({std::string(1, "xyz"[c]), {}});
      columns.back().values.reserve(soup.positions.size());
      for (const Vec3& p : soup.positions) columns.back().values.push_back(p[c]);
    }
    if (allNormals) addNormals();
    colorBegin = columns.size();
    if (anyColor) addColors(anyAlpha ? 4 : 3);
    colorEnd = columns.size();
    for (const auto& [name, dim] : extras) addExtra(name, dim);
    chooseTypes(anyColor);
  }

 private:
  template <class Value>
  void perVertex(const std::string& name, Value&& value) {
    static const std::vector<Eigen::Matrix4d> identity{Eigen::Matrix4d::Identity()};
    Column col{name, {}};
    col.values.reserve(columns.empty() ? 0 : columns.front().values.size());
    for (const auto& p : document_.parts)
      for (const auto& m : p.instances.empty() ? identity : p.instances)
        for (size_t v = 0; v < p.positions.size(); ++v) col.values.push_back(value(p, m, v));
    columns.push_back(std::move(col));
  }

  void addNormals() {
    for (int c = 0; c < 3; ++c)
      perVertex(std::string("n") + "xyz"[c], [c](const MeshPart& p, const Eigen::Matrix4d& m, size_t v) {
        const Eigen::Matrix3d nm = m.topLeftCorner<3, 3>().inverse().transpose();
        const Vec3 w = nm * p.normals[v];
        return (w.norm() > 0 ? Vec3(w.normalized()) : w)[c];
      });
  }

  void addColors(int channels) {
    static const char* const names[] = {"red", "green", "blue", "alpha"};
    for (int c = 0; c < channels; ++c)
      perVertex(names[c], [c](const MeshPart& p, const Eigen::Matrix4d&, size_t v) {
        return p.colors.empty() ? 1.0 : std::clamp(p.colors[v][c], 0.0, 1.0);
      });
  }

  // One property per component, named after the attribute without its leading '_'.
  void addExtra(const std::string& name, int dim) {
    const std::string base = !name.empty() && name[0] == '_' ? name.substr(1) : name;
    if (base.empty() || base.find_first_of(" \t\r\n") != std::string::npos) {
      warnings_.push_back(path_ + ": attribute '" + name + "' not written: not a valid PLY property name");
      return;
    }
    for (int k = 0; k < dim; ++k) {
      const std::string prop = dim == 1 ? base : base + "_" + std::to_string(k);
      if (reserved(prop)) {
        warnings_.push_back(path_ + ": attribute '" + name + "' not written: PLY property '" + prop + "' is taken");
        break;
      }
      perVertex(prop, [&, k](const MeshPart& p, const Eigen::Matrix4d&, size_t v) {
        for (const auto& e : p.extras)
          if (e.name == name) return e.values[v * dim + k];
        return 0.0;
      });
    }
    if (dim > 1)
      warnings_.push_back(path_ + ": attribute '" + name + "' (dimension " + std::to_string(dim) +
                          ") written as one PLY property per component, " + base + "_0 to " + base + "_" +
                          std::to_string(dim - 1));
  }

  // float where every value fits it exactly, else double; colors as uchar when all of them fit.
  void chooseTypes(bool anyColor) {
    for (size_t c = 0; c < columns.size(); ++c) {
      const bool color = c >= colorBegin && c < colorEnd;
      columns[c].bytes = color && allBytes(columns[c].values);
      columns[c].single = allFloat(columns[c].values);
    }
    if (anyColor && colorBegin < colorEnd) {
      // One type for all color channels: readers expect red, green and blue alike.
      bool bytes = true;
      for (size_t c = colorBegin; c < colorEnd; ++c) bytes = bytes && columns[c].bytes;
      for (size_t c = colorBegin; c < colorEnd; ++c) columns[c].bytes = bytes, columns[c].single = true;
    }
  }

  const Document& document_;
  const std::string& path_;
  std::vector<std::string>& warnings_;
};

// Header and binary little endian records: the vertex columns, then the triangles.
std::string encode(const std::vector<Column>& cols, const TriangleSoup& soup) {
  const size_t n = soup.positions.size();
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by geoshift\nelement vertex " +
                    std::to_string(n) + "\n";
  for (const Column& c : cols)
    out += std::string("property ") + (c.bytes ? "uchar" : c.single ? "float" : "double") + " " + c.name + "\n";
  out += "element face " + std::to_string(soup.faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  size_t record = 0;
  for (const Column& c : cols) record += c.bytes ? 1 : c.single ? 4 : 8;
  out.reserve(out.size() + n * record + soup.faces.size() * 13);
  LittleEndian le(out);
  for (size_t v = 0; v < n; ++v)
    for (const Column& c : cols) {
      const double x = c.values[v];
      if (c.bytes) le.put(static_cast<uint8_t>(std::lround(x * 255)));
      else if (c.single) le.put(static_cast<float>(x));
      else le.put(x);
    }
  for (const Face& f : soup.faces) {
    le.put(static_cast<uint8_t>(3));
    for (int k = 0; k < 3; ++k) le.put(static_cast<int32_t>(f[k]));
  }
  return out;
}

}  // namespace

std::vector<std::string> writePly(const Document& document, const std::string& path) {
  std::vector<std::string> warnings;
  const TriangleSoup soup = worldSoup(document);
  VertexColumns vertex(document, path, warnings);
  vertex.add(soup);
  AtomicFileSet files;
  files.add(path, encode(vertex.columns, soup));
  files.commit();
  return warnings;
}

}  // namespace geoshift::io

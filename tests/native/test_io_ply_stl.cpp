// PLY and STL meshes: round trips through the writers, the same mesh from ascii, binary little
// and binary big endian files written here by hand, welding of STL corners, every refusal with its
// message, and the real PLY files of ../shared/data (the CLI on them: test_cli_io.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "geoshift/error.hpp"
#include "geoshift/io.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/terrain.hpp"
#include "support.hpp"

using namespace geoshift;
using namespace geoshift::test;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// Binary values in either byte order, whatever the host's.
struct Bytes {
  bool big = false;
  std::string s;
  template <class T>
  Bytes& put(T v) {
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if (big != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
    s.append(raw, sizeof(T));
    return *this;
  }
};

// A square split into a quad and a triangle fan neighbour: 5 vertices with double positions,
// float normals, uchar colors and a short scalar "quality"; faces a quad (uchar count, int
// items) and a triangle.
const char* kHeaderTail =
    "element vertex 5\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\n"
    "property float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
    "property short quality\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
const double kPos[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.1, 2.3, -1e-7}};
const unsigned char kColor[5][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {10, 20, 30}, {1, 2, 3}};
const short kQuality[5] = {-3, 0, 7, 1000, -32768};

std::string asciiPly() {
  std::string s = std::string("ply\nformat ascii 1.0\ncomment by hand\n") + kHeaderTail;
  for (int v = 0; v < 5; ++v) {
    char line[200];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g 0 0 1 %d %d %d %d\n", kPos[v][0], kPos[v][1], kPos[v][2],
                  kColor[v][0], kColor[v][1], kColor[v][2], kQuality[v]);
    s += line;
  }
  return s + "4 0 1 2 3\n3 3 2 4\n";
}

std::string binaryPly(bool big) {
  Bytes b{big, std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" +
                   kHeaderTail};
  for (int v = 0; v < 5; ++v) {
    for (double c : kPos[v]) b.put(c);
    b.put(0.0f).put(0.0f).put(1.0f);
    for (unsigned char c : kColor[v]) b.put(c);
    b.put(kQuality[v]);
  }
  b.put(uint8_t(4)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2)).put(int32_t(3));
  b.put(uint8_t(3)).put(int32_t(3)).put(int32_t(2)).put(int32_t(4));
  return b.s;
}

void checkHandMade(const Document& doc) {
  REQUIRE(doc.parts.size() == 1);
  const MeshPart& p = doc.parts[0];
  REQUIRE(p.positions.size() == 5);
  for (int v = 0; v < 5; ++v) CHECK(p.positions[v] == Vec3(kPos[v][0], kPos[v][1], kPos[v][2]));
  CHECK(p.faces == std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {3, 2, 4}});
  REQUIRE(p.normals.size() == 5);
  CHECK(p.normals[4] == Vec3(0, 0, 1));
  REQUIRE(p.colors.size() == 5);
  CHECK(p.colors[3] == Eigen::Vector4d(10 / 255.0, 20 / 255.0, 30 / 255.0, 1));
  REQUIRE(p.extras.size() == 1);
  CHECK(p.extras[0].name == "_quality");
  CHECK(p.extras[0].values == std::vector<double>(kQuality, kQuality + 5));
  CHECK(anyContains(doc.warnings, "1 polygons with more than 3 vertices were fan-triangulated"));
}

std::string asciiStlCube(const TriangleSoup& s) {
  std::string t = "solid cube\n";
  for (const Face& f : s.faces) {
    t += "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = s.positions[f[k]];
      char line[120];
      std::snprintf(line, sizeof line, "      vertex %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
      t += line;
    }
    t += "    endloop\n  endfacet\n";
  }
  return t + "endsolid cube\n";
}

std::string binaryStl(const TriangleSoup& s, const std::string& header = "made by hand") {
  Bytes b;
  b.s = header;
  b.s.resize(80, ' ');
  b.put(static_cast<uint32_t>(s.faces.size()));
  for (const Face& f : s.faces) {
    b.put(0.0f).put(0.0f).put(0.0f);
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) b.put(static_cast<float>(s.positions[f[k]][c]));
    b.put(uint16_t(0));
  }
  return b.s;
}

// The soup with every corner replaced by its position: what welding must undo.
std::vector<std::array<Vec3, 3>> corners(const TriangleSoup& s) {
  std::vector<std::array<Vec3, 3>> c;
  for (const Face& f : s.faces) c.push_back({s.positions[f[0]], s.positions[f[1]], s.positions[f[2]]});
  return c;
}

}  // namespace

TEST_CASE("PLY: ascii, binary little and big endian give the same mesh", "[io][ply]") {
  const auto dir = tempDir("io-ply-encodings");
  spit(dir / "a.ply", asciiPly());
  spit(dir / "le.ply", binaryPly(false));
  spit(dir / "be.ply", binaryPly(true));
  for (const char* name : {"a.ply", "le.ply", "be.ply"}) {
    INFO(name);
    const Document doc = readDocument((dir / name).string());
    CHECK(doc.format == FileFormat::Ply);
    checkHandMade(doc);
  }
}

TEST_CASE("PLY: written and read back, positions, faces, normals, colors and attributes unchanged", "[io][ply]") {
  const auto dir = tempDir("io-ply-roundtrip");
  spit(dir / "be.ply", binaryPly(true));
  Document doc = readDocument((dir / "be.ply").string());
  doc.parts[0].positions[2] = Vec3(1.0 / 3, 2.0 / 3, 1e-300);  // not a float: written as double
  doc.parts[0].extras.push_back({"_TEMP", 1, {0.5, 1.5, 2.5, 3.5, 4.5}});
  CHECK(writeDocument(doc, (dir / "out.ply").string()).empty());
  const std::string bytes = slurp(dir / "out.ply");
  CHECK_THAT(bytes, Contains("format binary_little_endian 1.0"));
  CHECK_THAT(bytes, Contains("property double x") && Contains("property uchar red") &&
                        Contains("property float quality") && Contains("property float TEMP"));
  const Document again = readDocument((dir / "out.ply").string());
  REQUIRE(again.parts.size() == 1);
  const MeshPart &a = doc.parts[0], &b = again.parts[0];
  CHECK(b.positions == a.positions);
  CHECK(b.faces == a.faces);
  CHECK(b.normals == a.normals);
  CHECK(b.colors == a.colors);
  REQUIRE(b.extras.size() == 2);
  CHECK(b.extras[0].name == "_quality");
  CHECK(b.extras[0].values == a.extras[0].values);
  CHECK(b.extras[1].name == "_TEMP");
  CHECK(b.extras[1].values == a.extras[1].values);

  // Float colors with alpha, from a mesh built here (no source file): kept as float.
  Document fresh;
  fresh.parts.push_back(MeshPart{});
  MeshPart& m = fresh.parts[0];
  const TriangleSoup cube = shapes::cube();
  m.positions = cube.positions;
  m.faces = cube.faces;
  for (size_t v = 0; v < m.positions.size(); ++v) m.colors.emplace_back(0.1 * v, 0.5, 0.25, 0.75);
  writeDocument(fresh, (dir / "cube.ply").string());
  const MeshPart c = readDocument((dir / "cube.ply").string()).parts.at(0);
  CHECK(c.positions == m.positions);
  CHECK(c.faces == m.faces);
  REQUIRE(c.colors.size() == m.colors.size());
  for (size_t v = 0; v < m.colors.size(); ++v) CHECK((c.colors[v] - m.colors[v]).norm() < 1e-7);
}

TEST_CASE("PLY: any integer index type, vertex_index, color and alpha types", "[io][ply]") {
  const auto dir = tempDir("io-ply-types");
  Bytes b{true, "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nproperty ushort red\nproperty ushort green\nproperty ushort blue\n"
                "property ushort alpha\nproperty list uint char tags\nelement face 1\n"
                "property list ushort uint vertex_index\nproperty uchar flags\nelement edge 1\n"
                "property int vertex1\nproperty int vertex2\nend_header\n"};
  for (int v = 0; v < 3; ++v) {
    b.put(float(v == 1)).put(float(v == 2)).put(0.0f);
    b.put(uint16_t(65535)).put(uint16_t(0)).put(uint16_t(v * 100)).put(uint16_t(65535));
    b.put(uint32_t(2)).put(int8_t(-1)).put(int8_t(1));
  }
  b.put(uint16_t(3)).put(uint32_t(0)).put(uint32_t(1)).put(uint32_t(2)).put(uint8_t(9));
  b.put(int32_t(0)).put(int32_t(1));
  spit(dir / "t.ply", b.s);
  const Document doc = readDocument((dir / "t.ply").string());
  const MeshPart& p = doc.parts.at(0);
  CHECK(p.faces == std::vector<Face>{{0, 1, 2}});
  CHECK(p.colors[2] == Eigen::Vector4d(1, 0, 200 / 65535.0, 1));
  CHECK(p.extras.empty());
  CHECK(anyContains(doc.warnings, "vertex list property 'tags' is ignored"));
  CHECK(anyContains(doc.warnings, "face property 'flags' is ignored"));
  CHECK(anyContains(doc.warnings, "element 'edge' (1) is ignored"));
}

TEST_CASE("PLY: damaged files are refused naming the file, element, record and line", "[io][ply][errors]") {
  const auto dir = tempDir("io-ply-errors");
  auto err = [&](const std::string& name, const std::string& body, const ReadOptions& o = {}) {
    spit(dir / name, body);
    return errorOf([&] { readDocument((dir / name).string(), o); });
  };
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
  CHECK(err("ok.ply", head + verts + "3 0 1 2\n") == "(no error)");
  CHECK_THAT(err("range.ply", head + verts + "3 0 1 7\n"), Contains("range.ply:13: face 0: index 7 out of range (3 vertices)"));
  CHECK_THAT(err("neg.ply", head + verts + "3 0 -1 2\n"), Contains("neg.ply:13: face 0: index -1 out of range"));
  CHECK_THAT(err("two.ply", head + verts + "2 0 1\n"), Contains("two.ply:13: face 0: a face needs at least 3 vertices, this one has 2"));
  CHECK_THAT(err("word.ply", head + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), Contains("word.ply:11: vertex 1: 'x' is not a number (property 'y')"));
  CHECK_THAT(err("short.ply", head + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n"), Contains("short.ply:11: vertex 1: the line ends before property 'z'"));
  CHECK_THAT(err("long.ply", head + "0 0 0 9\n1 0 0\n0 1 0\n3 0 1 2\n"), Contains("long.ply:10: vertex 0: 1 more value(s) on the line"));
  CHECK_THAT(err("list.ply", head + verts + "5 0 1 2\n"), Contains("list.ply:13: face 0: list 'vertex_indices' declares 5 items, more than the line holds"));
  CHECK_THAT(err("cut.ply", head + verts), Contains("cut.ply: element 'face' declares 1 records, more than the remaining 0 bytes"));
  CHECK_THAT(err("frac.ply", head + verts + "3 0 1.5 2\n"), Contains("frac.ply:13: face 0: '1.5' is not a valid int (an item of list 'vertex_indices')"));
  CHECK_THAT(err("nan.ply", head + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), Contains("nan.ply:11: vertex 1: non-finite position"));
  CHECK_THAT(err("type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float128 x\nend_header\n"),
             Contains("type.ply: header line 4: unknown property type 'float128'"));
  CHECK_THAT(err("ftype.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                              "element face 1\nproperty list uchar float vertex_indices\nend_header\n" + verts + "3 0 1 2\n"),
             Contains("ftype.ply: face property 'vertex_indices' has item type float; indices must be integers"));
  CHECK_THAT(err("magic.ply", "plx\n"), Contains("magic.ply: not a PLY file"));
  CHECK_THAT(err("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), Contains("noend.ply: the PLY header has no end_header line"));
  CHECK_THAT(err("nov.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"),
             Contains("nov.ply: the PLY file has no vertex element"));
  CHECK_THAT(err("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"),
             Contains("noz.ply: the vertex element has no scalar property 'z'"));
  CHECK_THAT(err("noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n"),
             Contains("noface.ply: the file contains no triangles"));
  CHECK_THAT(err("limit.ply", head + verts + "3 0 1 2\n", ReadOptions{2}),
             Contains("limit.ply: element 'vertex' declares 3 vertices, more than the limit of 2 (raise it with --max-vertices)"));

  // Binary: counts beyond what the bytes can hold are refused from the header, before allocating.
  const std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  Bytes v;
  for (int i = 0; i < 9; ++i) v.put(float(i == 3 || i == 7));
  CHECK_THAT(err("bcut.ply", bin + v.s.substr(0, 30)),
             Contains("bcut.ply: element 'vertex' declares 3 records, more than the remaining 30 bytes of the file can hold"));
  CHECK_THAT(err("huge.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 4000000000000\nproperty double x\n"
                             "property double y\nproperty double z\nend_header\n" + std::string(64, '\0'), ReadOptions{~size_t(0)}),
             Contains("huge.ply: element 'vertex' declares 4000000000000 records, more than the remaining 64 bytes"));
  // An element without properties takes no bytes, so only an explicit rule bounds its count: a
  // 100-byte file declaring 10^12 such records must be refused at once, not looped over.
  CHECK_THAT(err("empty-element.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement nothing 1000000000000\nend_header\n" + v.s),
             Contains("empty-element.ply: element 'nothing' declares 1000000000000 records but no properties"));
  CHECK_THAT(err("ahuge.ply", "ply\nformat ascii 1.0\nelement vertex 30\nproperty float x\nproperty float y\nproperty float z\n"
                              "end_header\n" + verts),
             Contains("ahuge.ply: element 'vertex' declares 30 records, more than the remaining 18 bytes"));
  Bytes f = v;
  f.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1)).put(int32_t(3));
  CHECK_THAT(err("brange.ply", bin + f.s), Contains("brange.ply: face 0: index 3 out of range (3 vertices)"));
  Bytes g = v;
  g.put(uint8_t(200)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
  CHECK_THAT(err("blist.ply", bin + g.s), Contains("blist.ply: face 0: list 'vertex_indices' declares 200 items, more than the file holds"));
  Bytes h = v;
  h.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1));
  CHECK_THAT(err("btrunc.ply", bin + h.s), Contains("btrunc.ply: face 0: list 'vertex_indices' declares 3 items, more than the file holds"));
}

TEST_CASE("STL: ascii and binary give the same welded mesh", "[io][stl]") {
  const auto dir = tempDir("io-stl");
  const TriangleSoup cube = shapes::cube();
  spit(dir / "a.stl", asciiStlCube(cube));
  spit(dir / "b.stl", binaryStl(cube));
  spit(dir / "s.stl", binaryStl(cube, "solid but binary"));  // binary files may start with "solid"
  const Document a = readDocument((dir / "a.stl").string());
  const Document b = readDocument((dir / "b.stl").string());
  const Document s = readDocument((dir / "s.stl").string());
  CHECK(a.format == FileFormat::Stl);
  REQUIRE(a.parts.size() == 1);
  CHECK(a.parts[0].positions.size() == cube.positions.size());  // 36 corners welded to 8
  CHECK(a.parts[0].faces.size() == cube.faces.size());
  CHECK(corners(partSoup(a.parts[0])) == corners(cube));
  CHECK(b.parts[0].positions == a.parts[0].positions);
  CHECK(b.parts[0].faces == a.parts[0].faces);
  CHECK(s.parts[0].faces == a.parts[0].faces);

  // Written (binary) and read back: the same triangles, corner for corner.
  CHECK(writeDocument(b, (dir / "out.stl").string()).empty());
  const std::string out = slurp(dir / "out.stl");
  CHECK(out.size() == 84 + 50 * cube.faces.size());
  CHECK(out.compare(0, 5, "solid") != 0);
  const Document again = readDocument((dir / "out.stl").string());
  CHECK(again.parts[0].positions == b.parts[0].positions);
  CHECK(again.parts[0].faces == b.parts[0].faces);

  // PLY -> STL: positions only, and it says so.
  spit(dir / "c.ply", asciiPly());
  const Document ply = readDocument((dir / "c.ply").string());
  const auto warnings = writeDocument(ply, (dir / "c.stl").string());
  CHECK(anyContains(warnings, "STL stores positions only"));
  CHECK(anyContains(warnings, "attribute '_quality' is not stored in STL"));
  const MeshPart back = readDocument((dir / "c.stl").string()).parts.at(0);
  CHECK(back.faces == ply.parts[0].faces);
  for (size_t v = 0; v < back.positions.size(); ++v)
    CHECK((back.positions[v] - ply.parts[0].positions[v]).norm() < 1e-6);
}

TEST_CASE("STL: damaged files are refused naming the file, triangle and line", "[io][stl][errors]") {
  const auto dir = tempDir("io-stl-errors");
  auto err = [&](const std::string& name, const std::string& body, const ReadOptions& o = {}) {
    spit(dir / name, body);
    return errorOf([&] { readDocument((dir / name).string(), o); });
  };
  const TriangleSoup cube = shapes::cube();
  std::string bin = binaryStl(cube);
  CHECK_THAT(err("cut.stl", bin.substr(0, bin.size() - 10)),
             Contains("cut.stl: binary STL header declares 12 triangles, which need 684 bytes, but the file has 674"));
  std::string more = bin;
  more[80] = 13;
  CHECK_THAT(err("count.stl", more), Contains("count.stl: binary STL header declares 13 triangles"));
  CHECK_THAT(err("tiny.stl", "abc"), Contains("tiny.stl: not an STL file: 3 bytes"));
  std::string nan = bin;
  const float q = std::nanf("");
  std::memcpy(nan.data() + 84 + 50 * 4 + 12 + 12 * 2 + 4, &q, 4);
  CHECK_THAT(err("nan.stl", nan), Contains("nan.stl: triangle 4 vertex 2 has a non-finite coordinate"));
  CHECK_THAT(err("empty.stl", binaryStl(TriangleSoup{})), Contains("empty.stl: the file contains no triangles"));
  CHECK_THAT(err("limit.stl", bin, ReadOptions{7}),
             Contains("limit.stl: triangle") && Contains("more than 7 distinct vertices (raise the limit with --max-vertices)"));

  const std::string ascii = asciiStlCube(cube);
  std::string two = ascii;
  const size_t third = two.find("vertex", two.find("vertex", two.find("vertex") + 1) + 1);
  two.erase(third, two.find('\n', third) - third);  // triangle 0 keeps two vertices
  CHECK_THAT(err("two.stl", two), Contains("two.stl:7: expected 'vertex' (triangle 0 needs 3 vertices), found 'endloop'"));
  CHECK_THAT(err("word.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n"),
             Contains("word.stl:5: 'zero' is not a number (triangle 0 vertex 1)"));
  CHECK_THAT(err("trunc.stl", ascii.substr(0, ascii.find("endloop", ascii.size() / 2))),
             Contains("trunc.stl:") && Contains("truncated: the file ends where 'endloop' was expected"));
  CHECK_THAT(err("keyword.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                                "endfacet\nfacets\nendsolid\n"),
             Contains("keyword.stl:9: expected 'facet' or 'endsolid', found 'facets'"));
}

TEST_CASE("real PLY meshes", "[io][ply][data]") {
  const auto iron = sharedData("guided_denoising_bldeng/models/RealData/iron/iron.ply");
  GEOSHIFT_SKIP_IF_MISSING(iron, "iron.ply");
  const Document doc = readDocument(iron->string());
  const MeshPart& p = doc.parts.at(0);
  CHECK(p.positions.size() == 85574);  // counts from ../shared/data/README.md
  CHECK(p.faces.size() == 168285);
  REQUIRE(p.extras.size() == 1);
  CHECK(p.extras[0].name == "_value");
  const auto dir = tempDir("io-ply-real");
  writeDocument(doc, (dir / "iron.ply").string());
  const MeshPart back = readDocument((dir / "iron.ply").string()).parts.at(0);
  CHECK(back.positions == p.positions);
  CHECK(back.faces == p.faces);
  CHECK(back.extras.at(0).values == p.extras[0].values);

  const auto fc = sharedData("assimp_testmodels_debian/PLY/float-color.ply");
  GEOSHIFT_SKIP_IF_MISSING(fc, "float-color.ply");
  const MeshPart c = readDocument(fc->string()).parts.at(0);
  CHECK(c.positions.size() == 3);
  CHECK(c.faces.size() == 1);
  REQUIRE(c.colors.size() == 3);
  for (const auto& col : c.colors) CHECK(((col.array() >= 0) && (col.array() <= 1)).all());
}

TEST_CASE("PLY point sets go through the same parser: its messages and a class that is no integer", "[io][ply][terrain]") {
  const auto dir = tempDir("io-ply-points");
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                           "property float class\nend_header\n";
  spit(dir / "ok.ply", head + "0 0 0 2\n1 0 0 5\n");
  CHECK(readPlyPoints((dir / "ok.ply").string()).classes == std::vector<int>{2, 5});
  spit(dir / "class.ply", head + "0 0 0 2\n1 0 0 1e300\n");
  CHECK_THAT(errorOf([&] { readPlyPoints((dir / "class.ply").string()); }),
             Contains("class.ply:10: vertex 1: class '1e+300' is not an integer"));
  spit(dir / "word.ply", head + "0 0 0 2\n1 zero 0 5\n");
  CHECK_THAT(errorOf([&] { readPlyPoints((dir / "word.ply").string()); }),
             Contains("word.ply:10: vertex 1: 'zero' is not a number (property 'y')"));
}

// File I/O: OBJ and OFF reading and writing back, conversions between formats, and the real files
// of ../shared/data.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "geoshift/error.hpp"
#include "geoshift/io.hpp"
#include "gltf_fixture.hpp"
#include "support.hpp"

using namespace geoshift;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace geoshift::test;

TEST_CASE("OBJ: colors, normals, triangulation, byte-exact write back", "[io][obj]") {
  const auto dir = test::tempDir("io-obj");
  const std::string text =
      "# a quad and a triangle\r\nmtllib none.mtl\r\ng quad\r\nv 0 0 0 1 0 0\r\nv 1 0 0 0 1 0\r\n"
      "v 1 1 0 0 0 1\r\nv 0 1 0 0.5 0.5 0.5\r\nv 0.1 0.2 3e-1 1 1 1\r\nvt 0 0\r\nvn 0 0 1\r\nvn 0 1 0\r\n"
      "usemtl red\r\nf 1//1 2//1 3//1 4//1\r\ng tri\r\nf 1//1 3//1 5//2\r\n";
  spit(dir / "a.obj", text);
  Document doc = readDocument((dir / "a.obj").string());
  REQUIRE(doc.parts.size() == 1);
  const MeshPart& part = doc.parts[0];
  CHECK(part.positions.size() == 5);
  CHECK(part.positions[4] == Vec3(0.1, 0.2, 0.3));  // double precision, not float
  CHECK(part.faces.size() == 3);
  REQUIRE(part.colors.size() == 5);
  CHECK(part.colors[1] == Eigen::Vector4d(0, 1, 0, 1));
  REQUIRE(part.normals.size() == 5);
  CHECK(part.normals[4] == Vec3(0, 1, 0));
  CHECK(anyContains(doc.warnings, "none.mtl"));

  writeDocument(doc, (dir / "same.obj").string());
  CHECK(slurp(dir / "same.obj") == text);

  doc.parts[0].positions[1] = Vec3(2, 0.5, -1);
  doc.parts[0].colors[1] = Eigen::Vector4d(0.25, 0.5, 0.75, 1);
  writeDocument(doc, (dir / "moved.obj").string());
  std::string expected = text;
  expected.replace(expected.find("v 1 0 0 0 1 0"), 13, "v 2 0.5 -1 0.25 0.5 0.75");
  CHECK(slurp(dir / "moved.obj") == expected);

  // shared vertex with two different vn: no per-vertex normals
  spit(dir / "split.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 2//2 4//2 3//2\n");
  const Document split = readDocument((dir / "split.obj").string());
  CHECK(split.parts[0].normals.empty());
  CHECK(split.parts[0].colors.empty());

  spit(dir / "missing-vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  CHECK_THAT(errorOf([&] { readDocument((dir / "missing-vertex.obj").string()); }),
             Contains("missing-vertex.obj: face 1 (group '') references vertex 7 but the file has 3 vertices"));
  // Found by fuzz_obj (heap overflow reading normal 8 of 2): vn and vt references are checked too.
  spit(dir / "normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nvt 0 0\nf 1/1/8 3/1/1 2/1/1\n");
  CHECK_THAT(errorOf([&] { readDocument((dir / "normal.obj").string()); }),
             Contains("normal.obj: face 1 (group '') references normal 8 but the file has 2 normals"));
  spit(dir / "uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 3/1 2/5\n");
  CHECK_THAT(errorOf([&] { readDocument((dir / "uv.obj").string()); }),
             Contains("uv.obj: face 1 (group '') references texture coordinate 5 but the file has 1"));
  spit(dir / "short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
  CHECK_THAT(errorOf([&] { readDocument((dir / "short.obj").string()); }),
             Contains("short.obj:2: expected 3 coordinates for vertex 2"));
}

TEST_CASE("OFF: COFF colors, comments, polygons, errors with line numbers", "[io][off]") {
  const auto dir = test::tempDir("io-off");
  spit(dir / "c.off", "COFF\n# comment\n5 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n1 1 0 0 0 255\n"
                      "0 1 0 255 255 255\n9 9 9 0 0 0 # unused\n4 0 1 2 3\n3 1 4 2\n");
  Document doc = readDocument((dir / "c.off").string());
  REQUIRE(doc.parts.size() == 1);
  CHECK(doc.parts[0].faces == std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {1, 4, 2}});
  CHECK(doc.parts[0].colors[1] == Eigen::Vector4d(0, 1, 0, 1));
  doc.parts[0].positions[0] = Vec3(0.5, -0.5, 0.125);
  writeDocument(doc, (dir / "out.off").string());
  const Document again = readDocument((dir / "out.off").string());
  CHECK(again.parts[0].positions == doc.parts[0].positions);
  CHECK(again.parts[0].faces == doc.parts[0].faces);
  CHECK(again.parts[0].colors[1] == Eigen::Vector4d(0, 1, 0, 1));

  spit(dir / "float.off", "COFF 3 1 0\n0 0 0 0.5 0.5 0.5 1\n1 0 0 1 1 1 1\n0 1 0 0 0 0 1\n3 0 1 2\n");
  CHECK(readDocument((dir / "float.off").string()).parts[0].colors[0] == Eigen::Vector4d(0.5, 0.5, 0.5, 1));

  auto err = [&](const std::string& name, const std::string& body) {
    spit(dir / name, body);
    return errorOf([&] { readDocument((dir / name).string()); });
  };
  CHECK_THAT(err("few.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
             Contains("few.off: expected 4 vertices and 1 faces, the file has only 4 data lines"));
  CHECK_THAT(err("counts.off", "OFF\nthree 1 0\n"), Contains("counts.off:2: 'three' is not an integer (vertex count)"));
  CHECK_THAT(err("neg.off", "OFF\n-3 1 0\n"), Contains("neg.off:2: bad counts"));
  CHECK_THAT(err("token.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"),
             Contains("token.off:4: 'x' is not a number (vertex 1)"));
  CHECK_THAT(err("coords.off", "OFF\n# c\n3 1 0\n0 0 0\n1 0 0\n\n0 1\n3 0 1 2\n"),
             Contains("coords.off:7: expected 3 coordinates for vertex 2"));
  CHECK_THAT(err("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
             Contains("index.off:6: face 0 index 5 out of range (3 vertices)"));
}

TEST_CASE("cross-format writes build fresh files and say what was dropped", "[io][convert]") {
  const auto dir = test::tempDir("io-convert");
  spit(dir / "tri.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  Document doc = readDocument((dir / "tri.off").string());
  doc.parts[0].extras.push_back({"_CURV", 1, {0.1, 0.2, 0.3, 0.4}});
  for (const char* name : {"tri.glb", "tri.gltf"}) {
    const auto warnings = writeDocument(doc, (dir / name).string());
    CHECK(anyContains(warnings, "not carried over"));
    const Document g = readDocument((dir / name).string());
    REQUIRE(g.parts.size() == 1);
    CHECK(g.parts[0].positions == doc.parts[0].positions);
    CHECK(g.parts[0].faces == doc.parts[0].faces);
    REQUIRE(g.parts[0].extras.size() == 1);
    CHECK(g.parts[0].extras[0].values[2] == Approx(0.3));
  }

  // glTF with instances -> OBJ / OFF: world space, every instance
  writeModel(testModel(), dir / "model.glb");
  const Document model = readDocument((dir / "model.glb").string());
  CHECK(anyContains(writeDocument(model, (dir / "model.obj").string()), "not carried over"));
  const Document obj = readDocument((dir / "model.obj").string());
  const TriangleSoup world = worldSoup(model);
  CHECK(obj.parts[0].positions.size() == world.positions.size());
  CHECK(obj.parts[0].faces == world.faces);
  CHECK((obj.parts[0].positions[2] - Vec3(3, 4, 5)).norm() < 1e-12);
  writeDocument(model, (dir / "model.off").string());
  const Document off = readDocument((dir / "model.off").string());
  CHECK(off.parts[0].faces.size() == world.faces.size());
  CHECK(off.parts[0].colors.size() == world.positions.size());
}

// ---------------------------------------------------------------------------------------------
// Real files from ../shared/data (skipped when absent); counts from its README.

TEST_CASE("Khronos glTF samples read and write back", "[io][data]") {
  struct Sample {
    const char* file;
    size_t vertices, faces;
    bool colors;
  };
  const Sample samples[] = {{"Box.glb", 24, 12, false},
                            {"BoxTextured.glb", 24, 12, false},
                            {"Duck.glb", 2399, 4212, false},
                            {"VertexColorTest.glb", 72, 36, true},
                            {"BoxVertexColors.gltf", 24, 12, true}};
  const auto dir = test::tempDir("io-khronos");
  for (const auto& s : samples) {
    const auto path = test::sharedData(std::string("khronos_gltf_samples/") + s.file);
    GEOSHIFT_SKIP_IF_MISSING(path, s.file);
    INFO(s.file);
    Document doc = readDocument(path->string());
    size_t nv = 0, nf = 0;
    bool colors = false;
    for (const auto& p : doc.parts) {
      nv += p.positions.size();
      nf += p.faces.size();
      colors = colors || !p.colors.empty();
    }
    CHECK(nv == s.vertices);
    CHECK(nf == s.faces);
    CHECK(colors == s.colors);

    const fs::path same = dir / (std::string("same-") + s.file);
    writeDocument(doc, same.string());
    const auto a = loadModel(*path), b = loadModel(same);
    CHECK(a.accessors.size() == b.accessors.size());
    CHECK(a.materials.size() == b.materials.size());
    CHECK(a.nodes.size() == b.nodes.size());
    REQUIRE(a.images.size() == b.images.size());
    for (size_t i = 0; i < a.images.size(); ++i) CHECK(a.images[i].image == b.images[i].image);

    for (auto& p : doc.parts)
      for (auto& v : p.positions) v *= 1.5;
    const fs::path moved = dir / (std::string("moved-") + s.file);
    writeDocument(doc, moved.string());
    const Document again = readDocument(moved.string());
    REQUIRE(again.parts.size() == doc.parts.size());
    for (size_t p = 0; p < doc.parts.size(); ++p)
      for (size_t v = 0; v < doc.parts[p].positions.size(); ++v)
        REQUIRE((again.parts[p].positions[v] - doc.parts[p].positions[v]).norm() <=
                1e-6 * (1 + doc.parts[p].positions[v].norm()));
  }
  const auto vct = test::sharedData("khronos_gltf_samples/VertexColorTest.glb");
  GEOSHIFT_SKIP_IF_MISSING(vct, "VertexColorTest.glb");
  const Document doc = readDocument(vct->string());
  CHECK(doc.parts.at(1).colors.size() == doc.parts.at(1).positions.size());
  CHECK(doc.parts.at(0).colors.empty());
}

TEST_CASE("real OBJ and OFF files", "[io][data]") {
  const auto dir = test::tempDir("io-real");
  const auto fandisk = test::sharedData("guided_denoising_bldeng/models/Fandisk0.3/Original.obj");
  GEOSHIFT_SKIP_IF_MISSING(fandisk, "Fandisk0.3/Original.obj");
  const Document doc = readDocument(fandisk->string());
  CHECK(doc.parts.at(0).positions.size() == 6475);
  CHECK(doc.parts.at(0).faces.size() == 12946);
  writeDocument(doc, (dir / "fandisk.obj").string());
  CHECK(slurp(dir / "fandisk.obj") == slurp(*fandisk));

  const auto sphere = test::sharedData("cgal_debian_libcgal_demo/data/meshes/sphere.off");
  GEOSHIFT_SKIP_IF_MISSING(sphere, "sphere.off");
  const Document s = readDocument(sphere->string());
  CHECK(s.parts.at(0).positions.size() == 162);
  CHECK(s.parts.at(0).faces.size() == 320);

  const auto cube = test::sharedData("assimp_testmodels_debian/OBJ/cube_with_vertexcolors.obj");
  GEOSHIFT_SKIP_IF_MISSING(cube, "cube_with_vertexcolors.obj");
  const Document c = readDocument(cube->string());
  REQUIRE(c.parts.at(0).colors.size() == 8);
  CHECK(c.parts[0].colors[3].isApprox(Eigen::Vector4d(0.87843, 0, 0.03922, 1)));
  CHECK(c.parts[0].faces.size() == 12);
  CHECK(c.parts[0].normals.empty());  // vertex 1 uses vn 2, 4 and 6
}

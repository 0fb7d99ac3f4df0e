// File I/O: glTF models built here in memory (two primitives sharing POSITION, interleaved
// POSITION/NORMAL, normalized-ubyte colors, a texture with embedded bytes, a node hierarchy, an
// unindexed and a POINTS primitive), written with tinygltf, then read and written back by geoshift.
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


// ---------------------------------------------------------------------------------------------
// glTF read / write back

TEST_CASE("glTF test model reads parts, faces, colors, extras and instances", "[io][gltf]") {
  const auto dir = test::tempDir("io-read");
  for (const char* name : {"model.gltf", "model.glb"}) {
    SECTION(name) {
      writeModel(testModel(), dir / name);
      const Document doc = readDocument((dir / name).string());
      REQUIRE(doc.parts.size() == 3);
      CHECK(anyContains(doc.warnings, "mesh 1 'Loose' primitive 1 has mode POINTS"));

      const MeshPart& sq = doc.parts[0];
      CHECK(sq.label == "mesh 0 'Square' primitives 0,1");
      REQUIRE(sq.positions.size() == 4);
      CHECK(sq.positions[2] == Vec3(1, 1, 0));
      REQUIRE(sq.faces.size() == 2);
      CHECK(sq.faces[0] == Face{0, 1, 2});
      CHECK(sq.faces[1] == Face{0, 2, 3});
      REQUIRE(sq.normals.size() == 4);
      CHECK(sq.normals[3] == Vec3(0, 0, 1));
      REQUIRE(sq.colors.size() == 4);
      CHECK(sq.colors[0].isApprox(Eigen::Vector4d(1, 0, 0, 1)));
      CHECK(sq.colors[2][3] == Approx(128.0 / 255));
      CHECK(sq.colors[3][0] == Approx(0.2));
      REQUIRE(sq.extras.size() == 1);
      CHECK(sq.extras[0].name == "_TEMP");
      CHECK(sq.extras[0].values == std::vector<double>{10, 20, 30, 40});
      // root: T(1,2,3) S(2); child: T(0,0,1) -> vertex (1,1,0) lands at (3,4,5).
      REQUIRE(sq.instances.size() == 1);
      CHECK(((sq.instances[0] * Eigen::Vector4d(1, 1, 0, 1)).head<3>() - Vec3(3, 4, 5)).norm() < 1e-12);

      const MeshPart& loose = doc.parts[1];
      REQUIRE(loose.positions.size() == 6);
      CHECK(loose.faces == std::vector<Face>{{0, 1, 2}, {3, 4, 5}});
      CHECK(loose.instances.at(0).isIdentity());
      CHECK(doc.parts[2].positions == sq.positions);

      const TriangleSoup world = worldSoup(doc);
      CHECK(world.positions.size() == 14);
      CHECK(world.faces.size() == 5);
      CHECK(world.positions[2].isApprox(Vec3(3, 4, 5)));
      CHECK(partSoup(loose).faces.size() == 2);
    }
  }
}

TEST_CASE("glTF write back replaces geometry and keeps everything else", "[io][gltf]") {
  const auto dir = test::tempDir("io-writeback");
  for (const char* name : {"model.gltf", "model.glb"}) {
    SECTION(name) {
      const fs::path in = dir / name, out = dir / (std::string("out-") + name);
      writeModel(testModel(), in);
      const std::string inputBytes = slurp(in);
      Document doc = readDocument(in.string());
      for (auto& p : doc.parts[0].positions) p += Vec3(0.5, 0.25, 1.0 / 3.0);
      doc.parts[0].normals[0] = Vec3(0, 1, 0);
      doc.parts[0].colors[1] = Eigen::Vector4d(0.2, 0.4, 0.6, 1.0);
      doc.parts[0].extras[0].values[3] = 99;
      doc.parts[1].colors.assign(6, Eigen::Vector4d(0.5, 0.5, 0.5, 1));  // added: float VEC4
      doc.parts[1].extras.push_back({"_HEIGHT", 2, std::vector<double>(12, 1.5)});
      const auto warnings = writeDocument(doc, out.string());
      CHECK(warnings.empty());
      CHECK(slurp(in) == inputBytes);

      const Document again = readDocument(out.string());
      REQUIRE(again.parts.size() == 3);
      for (int v = 0; v < 4; ++v)
        CHECK((again.parts[0].positions[v] - doc.parts[0].positions[v]).norm() < 1e-6);
      CHECK(again.parts[0].normals[0] == Vec3(0, 1, 0));
      CHECK(again.parts[0].normals[1] == Vec3(0, 0, 1));
      CHECK(again.parts[0].colors[1].isApprox(Eigen::Vector4d(51, 102, 153, 255) / 255.0));
      CHECK(again.parts[0].colors[2][3] == Approx(128.0 / 255));
      CHECK(again.parts[0].extras[0].values[3] == 99);
      // mesh 2 shared the POSITION accessor: its vertices must not have moved.
      CHECK(again.parts[2].positions == readDocument(in.string()).parts[2].positions);
      CHECK(again.parts[1].colors.at(5).isApprox(Eigen::Vector4d(0.5, 0.5, 0.5, 1)));
      REQUIRE(again.parts[1].extras.size() == 1);
      CHECK(again.parts[1].extras[0].dim == 2);
      CHECK(again.parts[1].instances.size() == 1);
      CHECK(anyContains(again.warnings, "POINTS"));

      const auto a = loadModel(in), b = loadModel(out);
      CHECK(a.nodes.size() == b.nodes.size());
      CHECK(a.materials.size() == b.materials.size());
      CHECK(a.textures.size() == b.textures.size());
      CHECK(a.images.size() == b.images.size());
      CHECK(a.samplers.size() == b.samplers.size());
      CHECK(a.meshes[0].primitives[0].material == b.meshes[0].primitives[0].material);
      CHECK(b.materials[0].name == "painted");
      CHECK(b.materials[0].pbrMetallicRoughness.metallicFactor == 0.25);
      CHECK(b.materials[0].pbrMetallicRoughness.baseColorTexture.index == 0);
      CHECK(b.materials[0].extras.Get("note").Get<std::string>() == "keep me");
      CHECK(b.samplers[0].magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST);
      CHECK(b.nodes[0].extras.Get("id").Get<int>() == 7);
      CHECK(b.nodes[0].translation == a.nodes[0].translation);
      for (size_t i = 0; i < a.images.size(); ++i) CHECK(a.images[i].image == b.images[i].image);
      CHECK(std::string(b.images[0].image.begin(), b.images[0].image.end()) == kPngBytes);
      // POSITION min/max follow the data.
      const auto& acc = b.accessors[b.meshes[0].primitives[0].attributes.at("POSITION")];
      CHECK(acc.minValues[0] == Approx(0.5));
      CHECK(acc.maxValues[2] == Approx(1.0 / 3.0));
      // the POINTS primitive is untouched
      CHECK(b.meshes[1].primitives[1].mode == TINYGLTF_MODE_POINTS);
    }
  }
}

TEST_CASE("glTF round trip without changes keeps POSITION data exactly", "[io][gltf]") {
  const auto dir = test::tempDir("io-roundtrip");
  for (const char* name : {"model.gltf", "model.glb"}) {
    SECTION(name) {
      writeModel(testModel(), dir / name);
      const Document doc = readDocument((dir / name).string());
      const fs::path out = dir / (std::string("same-") + name);
      writeDocument(doc, out.string());
      const auto a = loadModel(dir / name), b = loadModel(out);
      REQUIRE(a.accessors.size() == b.accessors.size());  // nothing appended: all in place
      for (int acc : {0, 1, 2, 3}) {
        const auto& va = a.bufferViews[a.accessors[acc].bufferView];
        const auto& vb = b.bufferViews[b.accessors[acc].bufferView];
        CHECK(std::equal(a.buffers[0].data.begin() + va.byteOffset,
                         a.buffers[0].data.begin() + va.byteOffset + va.byteLength,
                         b.buffers[0].data.begin() + vb.byteOffset));
      }
      const Document again = readDocument(out.string());
      for (size_t p = 0; p < doc.parts.size(); ++p) {
        CHECK(again.parts[p].positions == doc.parts[p].positions);
        CHECK(again.parts[p].colors == doc.parts[p].colors);
      }
    }
  }
}

TEST_CASE("glTF with external .bin and image written to another directory", "[io][gltf]") {
  const auto dir = test::tempDir("io-external");
  const auto outDir = test::tempDir("io-external-out");
  tinygltf::Model model = testModel();
  tinygltf::Image external;
  external.uri = "tex%20file.png";
  model.images.push_back(external);
  spit(dir / "tex file.png", "external image bytes");
  writeModel(model, dir / "scene.gltf", false);
  REQUIRE(fs::exists(dir / "scene.bin"));
  const std::string binBefore = slurp(dir / "scene.bin");

  Document doc = readDocument((dir / "scene.gltf").string());
  doc.parts[1].positions[0] = Vec3(-1, -1, -1);
  writeDocument(doc, (outDir / "result.gltf").string());
  CHECK(slurp(dir / "scene.bin") == binBefore);
  CHECK(fs::exists(outDir / "result.bin"));
  CHECK(slurp(outDir / "tex file.png") == "external image bytes");
  CHECK(slurp(outDir / "result.gltf").find("\"result.bin\"") != std::string::npos);
  const Document again = readDocument((outDir / "result.gltf").string());
  CHECK(again.parts[1].positions[0] == Vec3(-1, -1, -1));
  const auto b = loadModel(outDir / "result.gltf");
  CHECK(b.images[2].uri == "tex%20file.png");
  CHECK(b.images[1].image == loadModel(dir / "scene.gltf").images[1].image);

  // the same document as .glb: one self-contained file plus the copied image
  writeDocument(doc, (outDir / "result.glb").string());
  CHECK(readDocument((outDir / "result.glb").string()).parts[1].positions[0] == Vec3(-1, -1, -1));
}

TEST_CASE("glTF sparse POSITION is applied on read and written densely", "[io][gltf]") {
  ModelBuilder b;
  const float base[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const int pos = b.accessor(b.view(base, sizeof base), 0, TINYGLTF_COMPONENT_TYPE_FLOAT, 3, TINYGLTF_TYPE_VEC3);
  b.m.accessors[pos].minValues = {0, 0, 0};
  b.m.accessors[pos].maxValues = {1, 1, 0};
  const uint16_t sidx[1] = {2};
  const float sval[3] = {0, 2, 5};
  auto& a = b.m.accessors[pos];
  a.sparse.isSparse = true;
  a.sparse.count = 1;
  a.sparse.indices.bufferView = b.view(sidx, 2, 0, 0);
  a.sparse.indices.byteOffset = 0;
  a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  b.m.accessors[pos].sparse.values.bufferView = b.view(sval, sizeof sval, 0, 0);
  b.m.accessors[pos].sparse.values.byteOffset = 0;
  b.m.accessors[pos].maxValues = {1, 2, 5};
  tinygltf::Mesh mesh;
  tinygltf::Primitive p;
  p.attributes["POSITION"] = pos;
  mesh.primitives.push_back(p);
  b.m.meshes.push_back(mesh);
  const auto dir = test::tempDir("io-sparse");
  writeModel(b.m, dir / "sparse.glb");
  Document doc = readDocument((dir / "sparse.glb").string());
  REQUIRE(doc.parts.size() == 1);
  CHECK(doc.parts[0].positions[2] == Vec3(0, 2, 5));
  CHECK(doc.parts[0].instances.at(0).isIdentity());  // drawn by no node
  doc.parts[0].positions[1] = Vec3(3, 0, 0);
  writeDocument(doc, (dir / "dense.glb").string());
  const Document again = readDocument((dir / "dense.glb").string());
  CHECK(again.parts[0].positions == doc.parts[0].positions);
  const auto m = loadModel(dir / "dense.glb");
  CHECK_FALSE(m.accessors[m.meshes[0].primitives[0].attributes.at("POSITION")].sparse.isSparse);
}

// ---------------------------------------------------------------------------------------------
// Bad input: every message names the file and what/where.

TEST_CASE("bad glTF input is reported clearly", "[io][errors]") {
  const auto dir = test::tempDir("io-bad-gltf");
  const std::string missing = (dir / "missing.glb").string();
  CHECK_THAT(errorOf([&] { readDocument(missing); }), Contains(missing) && Contains("not found"));
  CHECK_THAT(errorOf([&] { readDocument((dir / "mesh.3ds").string()); }),
             Contains("mesh.3ds") && Contains("unknown file extension '.3ds'"));

  spit(dir / "corrupt.glb", std::string("glTF\x02\0\0\0\xff\0\0\0garbage", 19));
  CHECK_THAT(errorOf([&] { readDocument((dir / "corrupt.glb").string()); }),
             Contains("corrupt.glb: cannot read glTF"));
  spit(dir / "corrupt.gltf", "{ not json");
  CHECK_THAT(errorOf([&] { readDocument((dir / "corrupt.gltf").string()); }),
             Contains("corrupt.gltf: cannot read glTF"));

  {
    tinygltf::Model m = testModel();
    m.meshes[0].primitives[1].extensions["KHR_draco_mesh_compression"] =
        tinygltf::Value(tinygltf::Value::Object{{"bufferView", tinygltf::Value(0)}});
    m.extensionsUsed.push_back("KHR_draco_mesh_compression");
    m.extensionsRequired.push_back("KHR_draco_mesh_compression");
    writeModel(m, dir / "draco.glb");
    CHECK_THAT(errorOf([&] { readDocument((dir / "draco.glb").string()); }),
               Contains("draco.glb: mesh 0 'Square' primitive 1 uses KHR_draco_mesh_compression; geoshift "
                        "cannot decode compressed geometry — decompress it first"));
  }
  {
    tinygltf::Model m = testModel();
    m.extensionsRequired.push_back("KHR_draco_mesh_compression");
    writeModel(m, dir / "draco-declared.gltf");
    CHECK_THAT(errorOf([&] { readDocument((dir / "draco-declared.gltf").string()); }),
               Contains("draco-declared.gltf: the file declares KHR_draco_mesh_compression"));
  }
  {
    tinygltf::Model m = testModel();
    m.bufferViews[0].extensions["EXT_meshopt_compression"] =
        tinygltf::Value(tinygltf::Value::Object{{"buffer", tinygltf::Value(0)}});
    m.extensionsUsed.push_back("EXT_meshopt_compression");
    writeModel(m, dir / "meshopt.gltf");
    // tinygltf 2.7 does not serialise buffer view extensions: add it to the JSON text.
    auto json = nlohmann::json::parse(slurp(dir / "meshopt.gltf"));
    json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0}};
    json["extensionsUsed"] = nlohmann::json::array();
    spit(dir / "meshopt.gltf", json.dump());
    CHECK_THAT(errorOf([&] { readDocument((dir / "meshopt.gltf").string()); }),
               Contains("meshopt.gltf: buffer view 0 uses EXT_meshopt_compression; geoshift cannot decode"));
  }
  {
    tinygltf::Model m = testModel();
    uint16_t bad[3] = {0, 2, 9};
    auto& d = m.buffers[0].data;
    std::memcpy(d.data() + m.bufferViews[m.accessors[5].bufferView].byteOffset, bad, 6);
    writeModel(m, dir / "range.glb");
    CHECK_THAT(errorOf([&] { readDocument((dir / "range.glb").string()); }),
               Contains("range.glb: mesh 0 'Square' primitive 1: triangle 0 uses index 9 out of range "
                        "(POSITION has 4 vertices)"));
  }
  {
    tinygltf::Model m = testModel();
    const float nan = std::nanf("");
    auto& d = m.buffers[0].data;
    std::memcpy(d.data() + m.bufferViews[m.accessors[6].bufferView].byteOffset + 4 * 12 + 4, &nan, 4);
    writeModel(m, dir / "nan.gltf");
    CHECK_THAT(errorOf([&] { readDocument((dir / "nan.gltf").string()); }),
               Contains("nan.gltf: mesh 1 'Loose' primitive 0: vertex 4 has a non-finite position"));
  }
  {
    tinygltf::Model m = testModel();
    for (auto& mesh : m.meshes)
      for (auto& p : mesh.primitives) p.mode = TINYGLTF_MODE_LINE;
    writeModel(m, dir / "lines.glb");
    CHECK_THAT(errorOf([&] { readDocument((dir / "lines.glb").string()); }),
               Contains("lines.glb: the file contains no triangles"));
  }
}

TEST_CASE("writing fails cleanly and leaves no partial file", "[io][errors]") {
  const auto dir = test::tempDir("io-bad-write");
  writeModel(testModel(), dir / "model.glb");
  Document doc = readDocument((dir / "model.glb").string());
  const std::string nowhere = (dir / "no" / "such" / "dir" / "out.glb").string();
  CHECK_THAT(errorOf([&] { writeDocument(doc, nowhere); }), Contains("does not exist"));
  CHECK_FALSE(fs::exists(dir / "no"));

  doc.parts[0].colors.pop_back();
  CHECK_THAT(errorOf([&] { writeDocument(doc, (dir / "out.glb").string()); }),
             Contains("out.glb: part 0 (mesh 0 'Square' primitives 0,1) has 3 colors for 4 positions"));
  doc = readDocument((dir / "model.glb").string());
  doc.parts[1].extras.push_back({"NOUNDERSCORE", 1, std::vector<double>(6, 0.0)});
  CHECK_THAT(errorOf([&] { writeDocument(doc, (dir / "out.glb").string()); }), Contains("must start with '_'"));
  doc.parts[1].extras.clear();
  doc.parts[1].positions.push_back(Vec3(0, 0, 0));
  CHECK_THAT(errorOf([&] { writeDocument(doc, (dir / "out.glb").string()); }),
             Contains("vertex layout cannot change"));
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"model.glb"});
}

// ---------------------------------------------------------------------------------------------
// OBJ and OFF

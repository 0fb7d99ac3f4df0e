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
#include "support.hpp"

using namespace geoshift;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

const std::string kPngBytes = std::string("\x89PNG\r\n\x1a\n", 8) + "not really a png, never decoded";
const std::string kDataUriImage = "data:image/png;base64,iVBORw0KGgpqdW5rIGJ5dGVz";  // \x89PNG\r\n\x1a\n"junk bytes"

struct ModelBuilder {
  tinygltf::Model m;
  ModelBuilder() {
    m.asset.version = "2.0";
    m.asset.generator = "geoshift test";
    m.buffers.emplace_back();
  }
  int view(const void* data, size_t bytes, size_t stride = 0, int target = TINYGLTF_TARGET_ARRAY_BUFFER) {
    auto& d = m.buffers[0].data;
    d.resize((d.size() + 3) / 4 * 4);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = d.size();
    v.byteLength = bytes;
    v.byteStride = stride;
    v.target = target;
    d.insert(d.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + bytes);
    m.bufferViews.push_back(v);
    return static_cast<int>(m.bufferViews.size()) - 1;
  }
  int accessor(int view, size_t offset, int ctype, size_t count, int type, bool normalized = false) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = offset;
    a.componentType = ctype;
    a.count = count;
    a.type = type;
    a.normalized = normalized;
    m.accessors.push_back(a);
    return static_cast<int>(m.accessors.size()) - 1;
  }
};

// Square (4 vertices, interleaved position+normal) as mesh 0 with two primitives sharing POSITION,
// two loose triangles plus a POINTS primitive as mesh 1, mesh 2 reusing mesh 0's POSITION.
tinygltf::Model testModel() {
  ModelBuilder b;
  const float interleaved[4][6] = {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {1, 1, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1}};
  const int iv = b.view(interleaved, sizeof interleaved, 24);
  const int pos = b.accessor(iv, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, 4, TINYGLTF_TYPE_VEC3);
  b.m.accessors[pos].minValues = {0, 0, 0};
  b.m.accessors[pos].maxValues = {1, 1, 0};
  const int nrm = b.accessor(iv, 12, TINYGLTF_COMPONENT_TYPE_FLOAT, 4, TINYGLTF_TYPE_VEC3);
  const uint8_t colors[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 128}, {51, 102, 153, 255}};
  const int col = b.accessor(b.view(colors, sizeof colors), 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 4,
                             TINYGLTF_TYPE_VEC4, true);
  const float temp[4] = {10, 20, 30, 40};
  const int tmp = b.accessor(b.view(temp, sizeof temp), 0, TINYGLTF_COMPONENT_TYPE_FLOAT, 4, TINYGLTF_TYPE_SCALAR);
  const uint8_t i8[3] = {0, 1, 2};
  const uint16_t i16[3] = {0, 2, 3};
  const int idx0 = b.accessor(b.view(i8, 3, 0, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER), 0,
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 3, TINYGLTF_TYPE_SCALAR);
  const int idx1 = b.accessor(b.view(i16, 6, 0, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER), 0,
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 3, TINYGLTF_TYPE_SCALAR);
  const float loose[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  const int lpos = b.accessor(b.view(loose, sizeof loose), 0, TINYGLTF_COMPONENT_TYPE_FLOAT, 6, TINYGLTF_TYPE_VEC3);
  b.m.accessors[lpos].minValues = {0, 0, 0};
  b.m.accessors[lpos].maxValues = {1, 1, 1};
  const int imgView = b.view(kPngBytes.data(), kPngBytes.size(), 0, 0);

  tinygltf::Mesh mesh0;
  mesh0.name = "Square";
  for (int idx : {idx0, idx1}) {
    tinygltf::Primitive p;
    p.attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"COLOR_0", col}, {"_TEMP", tmp}};
    p.indices = idx;
    p.material = 0;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    mesh0.primitives.push_back(p);
  }
  tinygltf::Mesh mesh1;
  mesh1.name = "Loose";
  tinygltf::Primitive tri;
  tri.attributes = {{"POSITION", lpos}};
  tri.mode = -1;  // absent: TRIANGLES
  mesh1.primitives.push_back(tri);
  tinygltf::Primitive pts;
  pts.attributes = {{"POSITION", lpos}};
  pts.mode = TINYGLTF_MODE_POINTS;
  mesh1.primitives.push_back(pts);
  tinygltf::Mesh mesh2;
  mesh2.name = "Alias";
  tinygltf::Primitive alias;
  alias.attributes = {{"POSITION", pos}};
  alias.indices = idx0;
  mesh2.primitives.push_back(alias);
  b.m.meshes = {mesh0, mesh1, mesh2};

  tinygltf::Material mat;
  mat.name = "painted";
  mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  mat.pbrMetallicRoughness.metallicFactor = 0.25;
  mat.extras = tinygltf::Value(tinygltf::Value::Object{{"note", tinygltf::Value(std::string("keep me"))}});
  b.m.materials.push_back(mat);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  b.m.samplers.push_back(sampler);
  tinygltf::Texture tex;
  tex.sampler = 0;
  tex.source = 0;
  b.m.textures.push_back(tex);
  tinygltf::Image embedded;
  embedded.bufferView = imgView;
  embedded.mimeType = "image/png";
  tinygltf::Image dataUri;
  dataUri.uri = kDataUriImage;
  b.m.images = {embedded, dataUri};

  tinygltf::Node root, child, looseNode, aliasNode;
  root.name = "root";
  root.translation = {1, 2, 3};
  root.scale = {2, 2, 2};
  root.children = {1};
  root.extras = tinygltf::Value(tinygltf::Value::Object{{"id", tinygltf::Value(7)}});
  child.mesh = 0;
  child.translation = {0, 0, 1};
  looseNode.mesh = 1;
  aliasNode.mesh = 2;
  aliasNode.translation = {5, 0, 0};
  b.m.nodes = {root, child, looseNode, aliasNode};
  tinygltf::Scene scene;
  scene.nodes = {0, 2, 3};
  b.m.scenes.push_back(scene);
  b.m.defaultScene = 0;
  return b.m;
}

bool keepUri(const std::string*, const std::string*, const tinygltf::Image* image, bool, std::string* out, void*) {
  *out = image->uri;
  return true;
}
bool rawImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
              int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

void writeModel(const tinygltf::Model& model, const fs::path& path, bool embedBuffers = true) {
  tinygltf::TinyGLTF t;
  t.SetImageWriter(keepUri, nullptr);
  REQUIRE(t.WriteGltfSceneToFile(&model, path.string(), false, embedBuffers, true, path.extension() == ".glb"));
}

tinygltf::Model loadModel(const fs::path& path) {
  tinygltf::TinyGLTF t;
  t.SetImageLoader(rawImage, nullptr);
  tinygltf::Model m;
  std::string err, warn;
  const bool ok = path.extension() == ".glb" ? t.LoadBinaryFromFile(&m, &err, &warn, path.string())
                                             : t.LoadASCIIFromFile(&m, &err, &warn, path.string());
  INFO(err);
  REQUIRE(ok);
  return m;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

bool anyContains(const std::vector<std::string>& v, const std::string& s) {
  for (const auto& x : v)
    if (x.find(s) != std::string::npos) return true;
  return false;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace


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
  CHECK_THAT(errorOf([&] { readDocument((dir / "mesh.stl").string()); }),
             Contains("mesh.stl") && Contains("unknown file extension '.stl'"));

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

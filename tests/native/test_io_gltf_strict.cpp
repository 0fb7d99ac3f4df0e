// glTF strictness and bounded work, on GLBs of a few hundred bytes assembled here byte by byte: every
// reference the schema forbids (negative or missing objects), accessors and buffer views that do
// not fit, strides shorter than their elements, index component types, and accessors without data
// declaring more elements than the --max-vertices limit (refused before anything is allocated).
#include <catch2/catch.hpp>

#include <cstring>

#include "geoshift/error.hpp"
#include "geoshift/io.hpp"
#include "glb_bytes.hpp"
#include "support.hpp"

using namespace geoshift;
using namespace geoshift::test;
using Catch::Matchers::Contains;
using nlohmann::json;
constexpr auto glb = glbBytes;

namespace {

// One triangle: POSITION (3 x VEC3 float, bytes 0-35) and uint16 indices (bytes 36-41).
json triangle() {
  return json::parse(R"({
    "asset": {"version": "2.0"},
    "buffers": [{"byteLength": 44}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "meshes": [{"name": "Tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})");
}

std::string triangleBin() {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t i[3] = {0, 1, 2};
  std::string b(44, '\0');
  std::memcpy(b.data(), p, 36);
  std::memcpy(b.data() + 36, i, 6);
  return b;
}

}  // namespace

TEST_CASE("glTF: references the schema forbids are errors naming the object", "[io][gltf][errors]") {
  const auto dir = tempDir("io-gltf-refs");
  auto read = [&](const std::string& name, const json& j, const ReadOptions& o = {}) {
    spit(dir / name, glb(j, triangleBin()));
    return errorOf([&] { readDocument((dir / name).string(), o); });
  };
  REQUIRE(read("ok.glb", triangle()) == "(no error)");
  {
    const Document doc = readDocument((dir / "ok.glb").string());
    CHECK(doc.parts.at(0).faces == std::vector<Face>{{0, 1, 2}});
  }
  json j = triangle();
  j["meshes"][0]["primitives"][0]["indices"] = -2;
  CHECK_THAT(read("neg-indices.glb", j),
             Contains("neg-indices.glb: mesh 0 'Tri' primitive 0 indices is -2: a negative index names no object "
                      "(the file has 2 accessors)"));
  j["meshes"][0]["primitives"][0]["indices"] = -1;  // -1 is what tinygltf uses for "absent"
  CHECK_THAT(read("neg1-indices.glb", j), Contains("mesh 0 'Tri' primitive 0 indices is -1: a negative index"));
  j = triangle();
  j["meshes"][0]["primitives"][0]["indices"] = 7;
  CHECK_THAT(read("big-indices.glb", j),
             Contains("mesh 0 'Tri' primitive 0 indices is 7, which names no object (the file has 2 accessors)"));
  j = triangle();
  j["meshes"][0]["primitives"][0]["indices"] = 1.5;
  CHECK_THAT(read("frac-indices.glb", j), Contains("mesh 0 'Tri' primitive 0 indices is 1.5, not the index of one of the accessors"));
  j = triangle();
  j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = -1;
  CHECK_THAT(read("neg-position.glb", j), Contains("mesh 0 'Tri' primitive 0 attribute POSITION is -1: a negative index"));
  j = triangle();
  j["accessors"][1]["bufferView"] = -3;
  CHECK_THAT(read("neg-view.glb", j), Contains("accessor 1 bufferView is -3: a negative index names no object (the file has 2 buffer views)"));
  j = triangle();
  j["bufferViews"][0]["buffer"] = -1;
  CHECK_THAT(read("neg-buffer.glb", j), Contains("buffer view 0 buffer is -1: a negative index names no object (the file has 1 buffers)"));
  j = triangle();
  j["nodes"][0]["mesh"] = 5;
  CHECK_THAT(read("node-mesh.glb", j), Contains("node 0 mesh is 5, which names no object (the file has 1 meshes)"));
  j = triangle();
  j["scenes"][0]["nodes"][0] = -4;
  CHECK_THAT(read("scene-node.glb", j), Contains("scene 0 nodes[0] is -4: a negative index"));
}

TEST_CASE("glTF: accessors and buffer views that do not fit, and short strides, are errors", "[io][gltf][errors]") {
  const auto dir = tempDir("io-gltf-bounds");
  auto read = [&](const std::string& name, const json& j, const ReadOptions& o = {}) {
    spit(dir / name, glb(j, triangleBin()));
    return errorOf([&] { readDocument((dir / name).string(), o); });
  };
  json j = triangle();
  j["accessors"][1]["count"] = 300;
  CHECK_THAT(read("index-count.glb", j),
             Contains("index-count.glb: mesh 0 'Tri' primitive 0 indices (accessor 1): 300 elements of 2 bytes (stride 2) "
                      "from byte 0 need 600 bytes, but buffer view 1 has 6"));
  j = triangle();
  j["accessors"][0]["count"] = 1000;
  CHECK_THAT(read("position-count.glb", j),
             Contains("POSITION (accessor 0): 1000 elements of 12 bytes (stride 12) from byte 0 need 12000 bytes, "
                      "but buffer view 0 has 36"));
  j = triangle();
  j["accessors"][0]["count"] = 4611686018427387904ull;  // (count - 1) * stride overflows 64 bits
  CHECK_THAT(read("overflow-count.glb", j, ReadOptions{~size_t(0)}),
             Contains("POSITION (accessor 0): 4611686018427387904 elements of 12 bytes") && Contains("but buffer view 0 has 36"));
  j = triangle();
  j["accessors"][0]["byteOffset"] = 28;
  CHECK_THAT(read("offset.glb", j), Contains("from byte 28 need 64 bytes, but buffer view 0 has 36"));
  j = triangle();
  j["bufferViews"][1]["byteOffset"] = 40;
  CHECK_THAT(read("view-outside.glb", j),
             Contains("view-outside.glb: mesh 0 'Tri' primitive 0 indices (accessor 1): buffer view 1 (bytes 40 to 46) "
                      "extends past the end of buffer 0 (44 bytes)"));
  j = triangle();
  j["bufferViews"][0]["byteStride"] = 8;
  CHECK_THAT(read("stride.glb", j),
             Contains("POSITION (accessor 0): buffer view 0 has byteStride 8, shorter than the accessor's 12-byte elements"));
  j = triangle();
  j["accessors"][0]["sparse"] = json::parse(
      R"({"count": 1, "indices": {"bufferView": 1, "componentType": 5120}, "values": {"bufferView": 0}})");
  CHECK_THAT(read("sparse-type.glb", j),
             Contains("POSITION (sparse accessor 0): sparse indices have component type 5120; they must be unsigned"));
  j["accessors"][0]["sparse"]["indices"]["componentType"] = 5123;
  j["accessors"][0]["sparse"]["count"] = 4;
  CHECK_THAT(read("sparse-count.glb", j), Contains("POSITION (sparse accessor 0): 4 sparse elements for 3"));
  j = triangle();
  j["accessors"][1]["componentType"] = 5122;  // SHORT: signed, not allowed for indices
  CHECK_THAT(read("index-type.glb", j),
             Contains("mesh 0 'Tri' primitive 0: indices accessor 1 has component type 5122; indices must be unsigned byte "
                      "(5121), unsigned short (5123) or unsigned int (5125)"));
}

TEST_CASE("glTF: accessors without data are bounded by --max-vertices before allocating", "[io][gltf][errors]") {
  const auto dir = tempDir("io-gltf-limit");
  // The issue's file: a POSITION accessor with no buffer view (legal: it reads as zeros) declaring
  // 400 million vertices. Refused at once with the default limit, not after gigabytes of zeros.
  json j = triangle();
  j["accessors"][0].erase("bufferView");
  j["accessors"][0]["count"] = 400000000;
  j["meshes"][0]["primitives"][0].erase("indices");
  spit(dir / "zeros.glb", glb(j, triangleBin()));
  CHECK(std::filesystem::file_size(dir / "zeros.glb") < 1000);
  CHECK_THAT(errorOf([&] { readDocument((dir / "zeros.glb").string()); }),
             Contains("zeros.glb: mesh 0 'Tri' primitive 0 POSITION (accessor 0) declares 400000000 vertices, more than "
                      "the limit of 50000000 (raise it with --max-vertices)"));
  // Within a raised limit the zeros are read (three of them: one degenerate triangle).
  j["accessors"][0]["count"] = 3;
  spit(dir / "three.glb", glb(j, triangleBin()));
  const Document doc = readDocument((dir / "three.glb").string(), ReadOptions{3});
  CHECK(doc.parts.at(0).positions == std::vector<Vec3>(3, Vec3::Zero()));
  // An index accessor without data: tinygltf refuses it outright (no allocation either).
  j = triangle();
  j["accessors"][1].erase("bufferView");
  j["accessors"][1]["count"] = 300000000;
  spit(dir / "index-zeros.glb", glb(j, triangleBin()));
  CHECK_THAT(errorOf([&] { readDocument((dir / "index-zeros.glb").string()); }),
             Contains("index-zeros.glb: cannot read glTF: accessor[1] invalid bufferView"));
}

TEST_CASE("glTF: node graphs are trees, and their instances are bounded by --max-vertices", "[io][gltf][errors]") {
  const auto dir = tempDir("io-gltf-nodes");
  auto write = [&](const std::string& name, const json& j) {
    spit(dir / name, glb(j, triangleBin()));
    return (dir / name).string();
  };
  // Wide: 1000 nodes draw the triangle. 3000 vertices in world space fit a limit of 3000; with a
  // limit of 2000 node 666 is the one too many (666 instances make 1998 vertices), refused while
  // the instances are gathered, before any world-space copy exists.
  json j = triangle();
  j["nodes"] = json::array();
  for (int n = 0; n < 1000; ++n) j["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, n}}});
  j["scenes"][0]["nodes"] = json::array({0});
  const std::string wide = write("wide.glb", j);
  const Document doc = readDocument(wide, ReadOptions{3000});
  REQUIRE(doc.parts.at(0).instances.size() == 1000);
  CHECK(doc.parts[0].instances[999](2, 3) == 999);
  CHECK(worldSoup(doc).positions.size() == 3000);
  CHECK_THAT(errorOf([&] { readDocument(wide, ReadOptions{2000}); }),
             Contains("wide.glb: node 666 draws mesh 0 'Tri' primitive 0 (3 vertices) once more: with it the nodes "
                      "draw more than 2000 vertices in world space, the limit (raise it with --max-vertices)"));
  // Deep: a chain of 100 000 nodes, each the child of the one before and one unit above it, the
  // last drawing the triangle. Composed without recursion: its world matrix lifts by 99 999 units.
  j = triangle();
  j["nodes"] = json::array();
  for (int n = 0; n < 100000; ++n) {
    json node = {{"translation", {0, 0, n == 0 ? 0 : 1}}};
    if (n + 1 < 100000) node["children"] = json::array({n + 1});
    else node["mesh"] = 0;
    j["nodes"].push_back(node);
  }
  const Document deep = readDocument(write("deep.glb", j));
  REQUIRE(deep.parts.at(0).instances.size() == 1);
  CHECK(deep.parts[0].instances[0](2, 3) == 99999);
  // Cycles and shared children: the schema's hierarchy is a set of disjoint trees.
  j = triangle();
  j["nodes"] = json::parse(R"([{"children": [1]}, {"children": [2]}, {"children": [0], "mesh": 0}])");
  CHECK_THAT(errorOf([&] { readDocument(write("cycle.glb", j)); }),
             Contains("cycle.glb: node 0 is its own ancestor (node 0 -> node 1 -> node 2 -> node 0, each the parent "
                      "of the next): a glTF node hierarchy may not contain cycles"));
  j["nodes"] = json::parse(R"([{"mesh": 0}, {"children": [1], "mesh": 0}])");
  CHECK_THAT(errorOf([&] { readDocument(write("self.glb", j)); }),
             Contains("self.glb: node 1 is its own ancestor (node 1 -> node 1, each the parent of the next)"));
  j["nodes"] = json::array();
  for (int n = 0; n < 20; ++n) j["nodes"].push_back({{"children", {(n + 1) % 20}}});
  CHECK_THAT(errorOf([&] { readDocument(write("long-cycle.glb", j)); }),
             Contains("node 0 is its own ancestor (node 0 -> node 1 -> node 2 -> node 3 -> node 4 -> node 5 -> node 6 "
                      "-> node 7 -> ... -> node 0,"));
  j["nodes"] = json::parse(R"([{"children": [2]}, {"children": [2]}, {"mesh": 0}])");
  CHECK_THAT(errorOf([&] { readDocument(write("two-parents.glb", j)); }),
             Contains("two-parents.glb: node 2 is a child of node 0 and of node 1: a glTF node has at most one parent"));
}

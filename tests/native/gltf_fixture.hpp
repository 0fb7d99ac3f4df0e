#pragma once
// A glTF model built in memory for the I/O tests (two primitives sharing POSITION, interleaved
// POSITION/NORMAL, normalized-ubyte colors, a texture with embedded bytes, a node hierarchy, an
// unindexed and a POINTS primitive), and tinygltf helpers that keep image bytes undecoded.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <string>

#include <tiny_gltf.h>

namespace geoshift::test {

namespace fs = std::filesystem;


inline const std::string kPngBytes = std::string("\x89PNG\r\n\x1a\n", 8) + "not really a png, never decoded";
inline const std::string kDataUriImage = "data:image/png;base64,iVBORw0KGgpqdW5rIGJ5dGVz";  // \x89PNG\r\n\x1a\n"junk bytes"

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
inline tinygltf::Model testModel() {
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

inline bool keepUri(const std::string*, const std::string*, const tinygltf::Image* image, bool, std::string* out, void*) {
  *out = image->uri;
  return true;
}
inline bool rawImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
              int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

inline void writeModel(const tinygltf::Model& model, const fs::path& path, bool embedBuffers = true) {
  tinygltf::TinyGLTF t;
  t.SetImageWriter(keepUri, nullptr);
  REQUIRE(t.WriteGltfSceneToFile(&model, path.string(), false, embedBuffers, true, path.extension() == ".glb"));
}

inline tinygltf::Model loadModel(const fs::path& path) {
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

}  // namespace geoshift::test

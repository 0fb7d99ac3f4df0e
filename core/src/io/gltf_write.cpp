// Writing geometry into glTF models: back into the model that was read (in place where an accessor
// belongs to one part and one semantic only, otherwise as new data appended to buffer 0), or into a
// minimal fresh model for documents read from another format.
#include <cstring>
#include <map>
#include <set>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

using Ref = std::pair<size_t, std::string>;  // part, semantic

int typeForComponents(int comps) {
  switch (comps) {
    case 1: return TINYGLTF_TYPE_SCALAR;
    case 2: return TINYGLTF_TYPE_VEC2;
    case 3: return TINYGLTF_TYPE_VEC3;
  }
  return TINYGLTF_TYPE_VEC4;
}

// Appends tightly packed elements to buffer 0 (the GLB BIN chunk) in a new buffer view. Vertex
// attribute elements must start on 4-byte boundaries, so small elements get a padded stride.
int appendAccessor(tinygltf::Model& model, const std::vector<double>& values, int comps,
                   int componentType, bool normalized, int target) {
  if (model.buffers.empty()) model.buffers.emplace_back();
  auto& data = model.buffers[0].data;
  const size_t csize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(componentType));
  const size_t elem = csize * comps;
  const bool vertexAttribute = target == TINYGLTF_TARGET_ARRAY_BUFFER;
  const size_t stride = vertexAttribute ? (elem + 3) / 4 * 4 : elem;
  const size_t count = values.size() / comps;
  data.resize((data.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = count == 0 ? 0 : (count - 1) * stride + elem;
  view.byteStride = stride != elem ? stride : 0;
  view.target = target;
  data.resize(data.size() + view.byteLength, 0);
  unsigned char* dst = data.data() + view.byteOffset;
  for (size_t i = 0; i < count; ++i)
    for (int k = 0; k < comps; ++k)
      storeComponent(dst + i * stride + k * csize, componentType, normalized, values[i * comps + k]);
  model.bufferViews.push_back(view);
  tinygltf::Accessor acc;
  acc.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  acc.byteOffset = 0;
  acc.componentType = componentType;
  acc.normalized = normalized;
  acc.count = count;
  acc.type = typeForComponents(comps);
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

std::vector<double> flatten3(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(v.size() * 3);
  for (const auto& p : v) out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

std::vector<double> flattenColors(const std::vector<Eigen::Vector4d>& c, int comps) {
  std::vector<double> out;
  out.reserve(c.size() * comps);
  for (const auto& p : c)
    for (int k = 0; k < comps; ++k) out.push_back(p[k]);
  return out;
}

class GltfWriteBack {
 public:
  GltfWriteBack(tinygltf::Model& model, const std::vector<GltfPartBinding>& parts)
      : model_(model), parts_(parts) {
    std::set<int> grouped;  // mesh * 2^20 + primitive
    for (size_t i = 0; i < parts.size(); ++i)
      for (int p : parts[i].primitives) {
        grouped.insert(parts[i].mesh * (1 << 20) + p);
        for (const auto& [sem, acc] : model.meshes[parts[i].mesh].primitives[p].attributes)
          refs_[acc].insert({i, sem});
      }
    // Everything else that reads an accessor keeps its data: it is passed through untouched.
    for (size_t m = 0; m < model.meshes.size(); ++m)
      for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
        const auto& prim = model.meshes[m].primitives[p];
        foreign_.insert(prim.indices);
        for (const auto& t : prim.targets)
          for (const auto& [sem, acc] : t) foreign_.insert(acc);
        if (!grouped.count(static_cast<int>(m) * (1 << 20) + static_cast<int>(p)))
          for (const auto& [sem, acc] : prim.attributes) foreign_.insert(acc);
      }
    for (const auto& s : model.skins) foreign_.insert(s.inverseBindMatrices);
    for (const auto& a : model.animations)
      for (const auto& s : a.samplers) foreign_.insert({s.input, s.output});
    for (size_t a = 0; a < model.accessors.size(); ++a) {
      const auto& acc = model.accessors[a];
      if (acc.bufferView < 0) continue;
      auto [it, added] = viewOffsetOwner_.emplace(std::make_pair(acc.bufferView, acc.byteOffset), static_cast<int>(a));
      if (!added) aliased_.insert({it->second, static_cast<int>(a)});
    }
  }

  // Replaces `semantic` of every primitive of part i with the values, in the given encoding.
  void set(size_t i, const std::string& semantic, const std::vector<double>& values, int comps,
           int componentType, bool normalized, bool minMax) {
    const auto& b = parts_[i];
    auto& mesh = model_.meshes[b.mesh];
    int existing = -2;
    for (int p : b.primitives) {
      const auto& attrs = mesh.primitives[p].attributes;
      const auto it = attrs.find(semantic);
      const int acc = it == attrs.end() ? -1 : it->second;
      existing = existing == -2 || existing == acc ? acc : -1;
    }
    // Unchanged data stays where it is, even in a shared accessor: a round trip adds nothing.
    if (existing >= 0 && holds(existing, values, comps, componentType, normalized)) return;
    if (existing >= 0 && canOverwrite(existing, i, semantic, comps, componentType)) {
      const AccessorLayout l = accessorLayout(model_, existing, "", "");
      unsigned char* dst = model_.buffers[l.buffer].data.data() + l.offset;
      auto& acc = model_.accessors[existing];
      for (size_t v = 0; v < acc.count; ++v)
        for (int k = 0; k < comps; ++k)
          storeComponent(dst + v * l.stride + k * l.componentSize, componentType, normalized || acc.normalized,
                         values[v * comps + k]);
      if (minMax || !acc.minValues.empty()) updateMinMax(model_, existing);
      return;
    }
    const int acc = appendAccessor(model_, values, comps, componentType, normalized,
                                   TINYGLTF_TARGET_ARRAY_BUFFER);
    if (minMax) updateMinMax(model_, acc);
    for (int p : b.primitives) mesh.primitives[p].attributes[semantic] = acc;
  }

  // The encoding COLOR_0 had (component type, VEC3/VEC4), or float VEC4 when there was none.
  std::pair<int, int> colorEncoding(size_t i) const {
    const auto& b = parts_[i];
    const auto& attrs = model_.meshes[b.mesh].primitives[b.primitives[0]].attributes;
    const auto it = attrs.find("COLOR_0");
    if (it == attrs.end() || it->second < 0 || static_cast<size_t>(it->second) >= model_.accessors.size())
      return {TINYGLTF_COMPONENT_TYPE_FLOAT, 4};
    const auto& acc = model_.accessors[it->second];
    const int comps = componentCount(acc.type);
    const int ct = acc.componentType;
    const bool known = ct == TINYGLTF_COMPONENT_TYPE_FLOAT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (!known || (comps != 3 && comps != 4)) return {TINYGLTF_COMPONENT_TYPE_FLOAT, 4};
    return {ct, comps};
  }

 private:
  bool holds(int a, const std::vector<double>& values, int comps, int componentType, bool normalized) const {
    const auto& acc = model_.accessors[a];
    if (acc.bufferView < 0 || acc.sparse.isSparse || acc.componentType != componentType ||
        componentCount(acc.type) != comps || acc.count * comps != values.size())
      return false;
    const AccessorLayout l = accessorLayout(model_, a, "", "");
    const unsigned char* stored = model_.buffers[l.buffer].data.data() + l.offset;
    unsigned char encoded[8];
    for (size_t v = 0; v < acc.count; ++v)
      for (int k = 0; k < comps; ++k) {
        const unsigned char* at = stored + v * l.stride + k * l.componentSize;
        storeComponent(encoded, componentType, normalized || acc.normalized, values[v * comps + k]);
        if (std::memcmp(encoded, at, l.componentSize) != 0) return false;
      }
    return true;
  }

  bool canOverwrite(int a, size_t part, const std::string& semantic, int comps, int componentType) const {
    const auto& acc = model_.accessors[a];
    const auto r = refs_.find(a);
    const bool exclusive = r != refs_.end() && r->second.size() == 1 &&
                           *r->second.begin() == Ref{part, semantic} && !foreign_.count(a);
    bool aliased = false;
    for (const auto& [x, y] : aliased_) aliased = aliased || x == a || y == a;
    return exclusive && !aliased && acc.bufferView >= 0 && !acc.sparse.isSparse &&
           acc.componentType == componentType && componentCount(acc.type) == comps;
  }

  tinygltf::Model& model_;
  const std::vector<GltfPartBinding>& parts_;
  std::map<int, std::set<Ref>> refs_;
  std::set<int> foreign_;
  std::map<std::pair<int, size_t>, int> viewOffsetOwner_;
  std::set<std::pair<int, int>> aliased_;
};

void checkExtraName(const std::string& path, const ExtraAttribute& e) {
  if (e.name.size() < 2 || e.name[0] != '_')
    fail(path, "extra attribute '" + e.name + "': glTF custom attribute names must start with '_'");
}

}  // namespace

std::vector<std::string> writeGltfInto(const Document& document, const std::string& path,
                                       FileFormat format) {
  const GltfSource& src = document.source->gltf;
  if (document.parts.size() != src.parts.size())
    fail(path, "the document has " + std::to_string(document.parts.size()) + " parts but " +
                   document.path + " had " + std::to_string(src.parts.size()) +
                   "; parts cannot be added or removed when writing back");
  tinygltf::Model model = src.model;
  GltfWriteBack writer(model, src.parts);
  for (size_t i = 0; i < document.parts.size(); ++i) {
    const MeshPart& part = document.parts[i];
    if (part.positions.size() != src.parts[i].vertexCount)
      fail(path, part.label + ": " + std::to_string(part.positions.size()) + " positions, the file has " +
                     std::to_string(src.parts[i].vertexCount) +
                     "; the vertex layout cannot change when writing back");
    for (const auto& e : part.extras) checkExtraName(path, e);
    writer.set(i, "POSITION", flatten3(part.positions), 3, TINYGLTF_COMPONENT_TYPE_FLOAT, false, true);
    if (!part.normals.empty())
      writer.set(i, "NORMAL", flatten3(part.normals), 3, TINYGLTF_COMPONENT_TYPE_FLOAT, false, false);
    if (!part.colors.empty()) {
      const auto [ct, comps] = writer.colorEncoding(i);
      writer.set(i, "COLOR_0", flattenColors(part.colors, comps), comps, ct,
                 ct != TINYGLTF_COMPONENT_TYPE_FLOAT, false);
    }
    for (const auto& e : part.extras)
      writer.set(i, e.name, e.values, e.dim, TINYGLTF_COMPONENT_TYPE_FLOAT, false, false);
  }
  AtomicFileSet files;
  auto warnings = serializeGltf(std::move(model), src.baseDir, path, format, files);
  files.commit();
  return warnings;
}

std::vector<std::string> writeGltfFresh(const Document& document, const std::string& path,
                                        FileFormat format) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "geoshift";
  model.buffers.emplace_back();
  tinygltf::Scene scene;
  for (size_t i = 0; i < document.parts.size(); ++i) {
    const MeshPart& part = document.parts[i];
    for (const auto& e : part.extras) checkExtraName(path, e);
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = appendAccessor(model, flatten3(part.positions), 3,
                                                 TINYGLTF_COMPONENT_TYPE_FLOAT, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    updateMinMax(model, prim.attributes["POSITION"]);
    std::vector<double> idx;
    idx.reserve(part.faces.size() * 3);
    for (const auto& f : part.faces) idx.insert(idx.end(), {double(f[0]), double(f[1]), double(f[2])});
    prim.indices = appendAccessor(model, idx, 1, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false,
                                  TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    if (!part.normals.empty())
      prim.attributes["NORMAL"] = appendAccessor(model, flatten3(part.normals), 3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                 false, TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!part.colors.empty())
      prim.attributes["COLOR_0"] = appendAccessor(model, flattenColors(part.colors, 4), 4,
                                                  TINYGLTF_COMPONENT_TYPE_FLOAT, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    for (const auto& e : part.extras)
      prim.attributes[e.name] = appendAccessor(model, e.values, e.dim, TINYGLTF_COMPONENT_TYPE_FLOAT, false,
                                               TINYGLTF_TARGET_ARRAY_BUFFER);
    tinygltf::Mesh mesh;
    mesh.name = part.label;
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    const auto instances = part.instances.empty() ? std::vector<Eigen::Matrix4d>{Eigen::Matrix4d::Identity()}
                                                  : part.instances;
    for (const auto& m : instances) {
      tinygltf::Node node;
      node.mesh = static_cast<int>(i);
      if (!m.isIdentity(0.0)) {
        node.matrix.resize(16);
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) node.matrix[c * 4 + r] = m(r, c);
      }
      scene.nodes.push_back(static_cast<int>(model.nodes.size()));
      model.nodes.push_back(node);
    }
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  AtomicFileSet files;
  auto warnings = serializeGltf(std::move(model), "", path, format, files);
  files.commit();
  return warnings;
}

}  // namespace geoshift::io

// glTF 2.0 reading through tinygltf: triangle primitives grouped by POSITION accessor into parts,
// node world matrices as instances, everything else kept in the model for writing back.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "io_detail.hpp"

namespace geoshift::io {
namespace {

const char* const kCompressedHint =
    "; geoshift cannot decode compressed geometry — decompress it first (e.g. gltf-transform copy)";

bool isCompression(const std::string& ext) {
  return ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression" ||
         ext == "KHR_meshopt_compression";
}

std::string meshLabel(const nlohmann::json& meshes, size_t m) {
  std::string name;
  if (m < meshes.size() && meshes[m].is_object() && meshes[m].contains("name") &&
      meshes[m]["name"].is_string())
    name = meshes[m]["name"].get<std::string>();
  return "mesh " + std::to_string(m) + " '" + name + "'";
}

void checkReferences(const std::string& path, const nlohmann::json& j);

// obj[key] when obj is an object holding an array there, else an empty array: a field of the
// wrong type ("primitives": 1) is tinygltf's to report, and must not be indexed as an array here.
const nlohmann::json& arrayAt(const nlohmann::json& obj, const char* key) {
  static const nlohmann::json empty = nlohmann::json::array();
  if (!obj.is_object()) return empty;
  const auto it = obj.find(key);
  return it != obj.end() && it->is_array() ? *it : empty;
}

// Compressed content is found in the JSON before tinygltf sees it: tinygltf may fail on a meshopt
// fallback buffer without a URI, which would hide the real reason.
void checkJson(const std::string& path, const std::string& jsonText) {
  const auto j = nlohmann::json::parse(jsonText, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return;  // tinygltf reports the syntax error
  const auto& meshes = arrayAt(j, "meshes");
  for (size_t m = 0; m < meshes.size(); ++m) {
    if (!meshes[m].is_object()) continue;
    const auto& prims = arrayAt(meshes[m], "primitives");
    for (size_t p = 0; p < prims.size(); ++p) {
      if (!prims[p].is_object() || !prims[p].contains("extensions")) continue;
      for (const auto& [ext, v] : prims[p]["extensions"].items())
        if (isCompression(ext))
          fail(path, meshLabel(meshes, m) + " primitive " + std::to_string(p) + " uses " + ext +
                         kCompressedHint);
    }
  }
  const auto& views = arrayAt(j, "bufferViews");
  for (size_t v = 0; v < views.size(); ++v) {
    if (!views[v].is_object() || !views[v].contains("extensions")) continue;
    for (const auto& [ext, val] : views[v]["extensions"].items())
      if (isCompression(ext))
        fail(path, "buffer view " + std::to_string(v) + " uses " + ext + kCompressedHint);
  }
  for (const char* key : {"extensionsRequired", "extensionsUsed"})
    for (const auto& ext : arrayAt(j, key))
      if (ext.is_string() && isCompression(ext.get<std::string>()))
        fail(path, "the file declares " + ext.get<std::string>() + " in " + key + kCompressedHint);
  checkReferences(path, j);
}

// glTF 2.0 schema: every reference to another object is an integer >= 0 naming an existing one.
// tinygltf reads such fields without checking them (a negative `indices` would read as "no
// indices"), so they are checked here, on the JSON, with the referring object named.
void checkReferences(const std::string& path, const nlohmann::json& j) {
  // The top-level lists and a mesh's primitives are arrays (schema); tinygltf would read another
  // type as "none" and the file as one without triangles, hiding what is wrong.
  auto arr = [&](const nlohmann::json& obj, const char* key, const std::string& where) -> const nlohmann::json& {
    if (obj.is_object() && obj.contains(key) && !obj[key].is_array())
      fail(path, where + key + " is " + obj[key].dump().substr(0, 40) + ", not an array");
    return arrayAt(obj, key);
  };
  const nlohmann::json &meshes = arr(j, "meshes", ""), &accessors = arr(j, "accessors", ""),
                       &views = arr(j, "bufferViews", ""), &buffers = arr(j, "buffers", ""),
                       &nodes = arr(j, "nodes", ""), &scenes = arr(j, "scenes", ""),
                       &materials = arr(j, "materials", ""), &images = arr(j, "images", ""),
                       &textures = arr(j, "textures", ""), &samplers = arr(j, "samplers", ""),
                       &cameras = arr(j, "cameras", ""), &skins = arr(j, "skins", "");
  auto check = [&](const nlohmann::json& v, const std::string& what, const nlohmann::json& targets,
                   const char* kind) {
    const std::string have = " (the file has " + std::to_string(targets.size()) + " " + kind + ")";
    if (!v.is_number_integer() && !v.is_number_unsigned())
      fail(path, what + " is " + v.dump().substr(0, 40) + ", not the index of one of the " + kind + have);
    if (v.is_number_integer() && v.get<long long>() < 0)
      fail(path, what + " is " + v.dump() + ": a negative index names no object" + have);
    if (v.get<unsigned long long>() >= targets.size())
      fail(path, what + " is " + v.dump() + ", which names no object" + have);
  };
  auto field = [&](const nlohmann::json& obj, const char* key, const std::string& what,
                   const nlohmann::json& targets, const char* kind) {
    if (obj.is_object() && obj.contains(key)) check(obj[key], what + " " + key, targets, kind);
  };
  auto list = [&](const nlohmann::json& obj, const char* key, const std::string& what,
                  const nlohmann::json& targets, const char* kind) {
    if (!obj.is_object() || !obj.contains(key) || !obj[key].is_array()) return;
    for (size_t i = 0; i < obj[key].size(); ++i)
      check(obj[key][i], what + " " + key + "[" + std::to_string(i) + "]", targets, kind);
  };
  for (size_t m = 0; m < meshes.size(); ++m) {
    const auto& prims = arr(meshes[m], "primitives", meshLabel(meshes, m) + " ");
    for (size_t p = 0; p < prims.size(); ++p) {
      const std::string what = meshLabel(meshes, m) + " primitive " + std::to_string(p);
      field(prims[p], "indices", what, accessors, "accessors");
      field(prims[p], "material", what, materials, "materials");
      if (prims[p].is_object() && prims[p].contains("attributes") && prims[p]["attributes"].is_object())
        for (const auto& [semantic, v] : prims[p]["attributes"].items())
          check(v, what + " attribute " + semantic, accessors, "accessors");
      if (prims[p].is_object() && prims[p].contains("targets") && prims[p]["targets"].is_array())
        for (size_t t = 0; t < prims[p]["targets"].size(); ++t)
          if (prims[p]["targets"][t].is_object())
            for (const auto& [semantic, v] : prims[p]["targets"][t].items())
              check(v, what + " morph target " + std::to_string(t) + " " + semantic, accessors, "accessors");
    }
  }
  for (size_t a = 0; a < accessors.size(); ++a) {
    const std::string what = "accessor " + std::to_string(a);
    field(accessors[a], "bufferView", what, views, "buffer views");
    if (accessors[a].is_object() && accessors[a].contains("sparse") && accessors[a]["sparse"].is_object()) {
      const auto& sp = accessors[a]["sparse"];
      for (const char* part : {"indices", "values"})
        if (sp.contains(part)) field(sp[part], "bufferView", what + " sparse " + part, views, "buffer views");
    }
  }
  for (size_t v = 0; v < views.size(); ++v)
    field(views[v], "buffer", "buffer view " + std::to_string(v), buffers, "buffers");
  for (size_t n = 0; n < nodes.size(); ++n) {
    const std::string what = "node " + std::to_string(n);
    field(nodes[n], "mesh", what, meshes, "meshes");
    field(nodes[n], "camera", what, cameras, "cameras");
    field(nodes[n], "skin", what, skins, "skins");
    list(nodes[n], "children", what, nodes, "nodes");
  }
  for (size_t sc = 0; sc < scenes.size(); ++sc) list(scenes[sc], "nodes", "scene " + std::to_string(sc), nodes, "nodes");
  if (j.contains("scene")) check(j["scene"], "the default scene", scenes, "scenes");
  for (size_t i = 0; i < images.size(); ++i) field(images[i], "bufferView", "image " + std::to_string(i), views, "buffer views");
  for (size_t t = 0; t < textures.size(); ++t) {
    field(textures[t], "source", "texture " + std::to_string(t), images, "images");
    field(textures[t], "sampler", "texture " + std::to_string(t), samplers, "samplers");
  }
}

// Images are kept as the bytes of the file: decoding and re-encoding would change them.
bool keepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

Eigen::Matrix4d localMatrix(const tinygltf::Node& n) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (n.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[c * 4 + r];  // column-major in glTF
    return m;
  }
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  if (n.translation.size() == 3) a.translate(Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    a.rotate(Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]).normalized());
  if (n.scale.size() == 3) a.scale(Eigen::Vector3d(n.scale[0], n.scale[1], n.scale[2]));
  return a.matrix();
}

// World matrices of all nodes. The schema makes the node hierarchy a set of disjoint trees: a node
// listed as the child of two nodes, or its own ancestor, is an error naming it. Iterative, so that a
// chain of a million nodes (a few MB of JSON) needs no deep stack.
std::vector<Eigen::Matrix4d> worldMatrices(const tinygltf::Model& model, const std::string& path) {
  const size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i)
    for (int c : model.nodes[i].children) {
      if (c < 0 || static_cast<size_t>(c) >= n) continue;  // checkReferences refused these
      if (parent[c] >= 0)
        fail(path, "node " + std::to_string(c) + " is a child of node " + std::to_string(parent[c]) + " and of node " +
                       std::to_string(i) + ": a glTF node has at most one parent (the hierarchy is a set of trees)");
      parent[c] = static_cast<int>(i);
    }
  std::vector<Eigen::Matrix4d> world(n);
  std::vector<char> state(n, 0);  // 0 todo, 1 on the current chain, 2 done
  std::vector<int> chain;
  for (size_t start = 0; start < n; ++start) {
    // Climb to the first ancestor already done (or the root), then compose back down.
    chain.clear();
    int i = static_cast<int>(start);
    while (i >= 0 && state[i] == 0) {
      state[i] = 1;
      chain.push_back(i);
      i = parent[i];
    }
    if (i >= 0 && state[i] == 1) {
      std::vector<int> cycle{i};  // upwards from i back to i, then read downwards
      for (int k = parent[i]; k != i; k = parent[k]) cycle.push_back(k);
      cycle.push_back(i);
      std::string text;
      for (size_t k = cycle.size(); k-- > 0;) {
        if (cycle.size() > 10 && k == cycle.size() - 9) {
          text += " -> ...";
          k = 1;
          continue;
        }
        text += (text.empty() ? "node " : " -> node ") + std::to_string(cycle[k]);
      }
      fail(path, "node " + std::to_string(i) + " is its own ancestor (" + text +
                     ", each the parent of the next): a glTF node hierarchy may not contain cycles");
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int c = *it;
      world[c] = parent[c] >= 0 ? Eigen::Matrix4d(world[parent[c]] * localMatrix(model.nodes[c]))
                                : localMatrix(model.nodes[c]);
      state[c] = 2;
    }
  }
  return world;
}

const char* modeName(int mode) {
  switch (mode) {
    case 0: return "POINTS";
    case 1: return "LINES";
    case 2: return "LINE_LOOP";
    case 3: return "LINE_STRIP";
    case 5: return "TRIANGLE_STRIP";
    case 6: return "TRIANGLE_FAN";
  }
  return "unknown";
}

// The accessor every primitive of the group uses for `semantic`, or -1 when absent or not shared.
int sharedAttribute(const tinygltf::Mesh& mesh, const GltfPartBinding& b, const std::string& semantic,
                    bool& inconsistent) {
  int found = -2;
  for (int p : b.primitives) {
    const auto& attrs = mesh.primitives[p].attributes;
    const auto it = attrs.find(semantic);
    const int acc = it == attrs.end() ? -1 : it->second;
    if (found == -2) found = acc;
    else if (found != acc) inconsistent = true;
  }
  return inconsistent ? -1 : found;
}

// The checks tinygltf does not make, or makes with a vaguer message, before it parses: the GLB
// header (version, length, an empty BIN chunk) and the JSON (checkJson). Returns whether the file
// is binary (GLB).
bool checkFileHead(const std::string& path, const std::string& bytes, FileFormat format) {
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  if (!binary) {
    const size_t first = bytes.find_first_not_of(" \t\r\n");
    if (format == FileFormat::Glb && (first == std::string::npos || bytes[first] != '{'))
      fail(path, "not a GLB file: it does not start with the 'glTF' signature (nor is it glTF JSON)");
    checkJson(path, bytes);
    return false;
  }
  // GLB header: magic, version, total length (tinygltf reads version 1 files and reports a short
  // file only as "Invalid glTF binary").
  uint32_t header[3] = {};
  std::memcpy(header, bytes.data(), std::min<size_t>(bytes.size(), sizeof header));
  if (bytes.size() >= 8 && header[1] != 2)
    fail(path, "cannot read glTF: GLB version " + std::to_string(header[1]) + "; geoshift reads glTF 2.0 (version 2)");
  if (bytes.size() >= 12 && header[2] > bytes.size())
    fail(path, "cannot read glTF: the GLB header says " + std::to_string(header[2]) + " bytes, the file has " +
                   std::to_string(bytes.size()) + " (truncated file)");
  // GLB: JSON chunk length at byte 12, chunk data at byte 20.
  if (bytes.size() >= 20) {
    uint32_t len = 0;
    std::memcpy(&len, bytes.data() + 12, 4);
    // Compared as lengths left after the header, so that nothing wraps where size_t is 32 bits.
    const size_t afterHeader = bytes.size() - 20;
    if (len <= afterHeader) checkJson(path, bytes.substr(20, len));
    // tinygltf refuses an empty BIN chunk as "must have 4 bytes or more, but got 4".
    uint32_t bin[2] = {};
    if (len <= afterHeader && afterHeader - len >= 8) std::memcpy(bin, bytes.data() + 20 + len, 8);
    if (bin[1] == 0x004e4942 && bin[0] == 0)
      fail(path, "cannot read glTF: the GLB has an empty BIN chunk (0 bytes); a GLB without binary data has no BIN chunk");
  }
  return true;
}

// tinygltf's parse into g.model; its warnings, one per line, go to `warnings`.
void loadModel(const std::string& path, const std::string& bytes, bool binary, GltfSource& g,
               std::vector<std::string>& warnings) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keepImageBytes, nullptr);
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool ok = binary ? loader.LoadBinaryFromMemory(&g.model, &err, &warn, data,
                                                       static_cast<unsigned>(bytes.size()), g.baseDir)
                         : loader.LoadASCIIFromString(&g.model, &err, &warn, bytes.data(),
                                                      static_cast<unsigned>(bytes.size()), g.baseDir);
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  if (!ok) fail(path, "cannot read glTF: " + (err.empty() ? std::string("unknown error") : err));
  std::istringstream ws(warn);
  for (std::string line; std::getline(ws, line);)
    if (!line.empty()) warnings.push_back(path + ": " + line);
}

// The parts of the model: per mesh, its TRIANGLES primitives grouped by POSITION accessor (the
// others are passed through with a warning).
void bindParts(const std::string& path, GltfSource& g, std::vector<std::string>& warnings) {
  const tinygltf::Model& model = g.model;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const auto& mesh = model.meshes[m];
    const std::string mlabel = "mesh " + std::to_string(m) + " '" + mesh.name + "'";
    std::map<int, size_t> groupOf;  // POSITION accessor -> binding index
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const auto& prim = mesh.primitives[p];
      const std::string plabel = mlabel + " primitive " + std::to_string(p);
      if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
        warnings.push_back(path + ": " + plabel + " has mode " + modeName(prim.mode) + " (" + std::to_string(prim.mode) +
                           "); passed through untouched (geoshift filters TRIANGLES only)");
        continue;
      }
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) {
        warnings.push_back(path + ": " + plabel + " has no POSITION; passed through untouched");
        continue;
      }
      // tinygltf does not check accessor indices; .at() below relies on this.
      for (const auto& [semantic, acc] : prim.attributes)
        if (acc < 0 || static_cast<size_t>(acc) >= model.accessors.size())
          fail(path, plabel + ": " + semantic + " names accessor " + std::to_string(acc) + ", which does not exist");
      if (prim.indices >= static_cast<int>(model.accessors.size()))
        fail(path, plabel + ": indices name accessor " + std::to_string(prim.indices) + ", which does not exist");
      auto [it, added] = groupOf.emplace(pos->second, g.parts.size());
      if (added) {
        GltfPartBinding b;
        b.mesh = static_cast<int>(m);
        b.positionAccessor = pos->second;
        g.parts.push_back(b);
      }
      g.parts[it->second].primitives.push_back(static_cast<int>(p));
    }
  }
}

// Reads one bound part after another into MeshParts: positions, triangles, the attributes the
// filters use, and one instance per node that draws it. Counts the world-space vertices of all
// instances (what worldSoup and the writers in world space allocate): bounded like the vertices of
// one accessor, and by what an int index can address.
class PartReader {
 public:
  PartReader(const std::string& path, const tinygltf::Model& model, const ReadOptions& options,
             std::vector<std::string>& warnings)
      : path_(path), model_(model), options_(options), warnings_(warnings), world_(worldMatrices(model, path)),
        nodesOfMesh_(model.meshes.size()),
        worldLimit_(std::min<size_t>(options.maxVertices, std::numeric_limits<int>::max())) {
    for (size_t n = 0; n < model.nodes.size(); ++n)
      if (model.nodes[n].mesh >= 0 && static_cast<size_t>(model.nodes[n].mesh) < model.meshes.size())
        nodesOfMesh_[model.nodes[n].mesh].push_back(static_cast<int>(n));
  }

  MeshPart read(GltfPartBinding& b) {
    MeshPart part;
    part.label = labelOf(b);
    readPositions(b, part);
    for (int p : b.primitives) readTriangles(b, p, part);
    readAttributes(b, part);
    placeInstances(b, part);
    return part;
  }

 private:
  std::string labelOf(const GltfPartBinding& b) const {
    std::string label = "mesh " + std::to_string(b.mesh) + " '" + model_.meshes[b.mesh].name + "' primitive";
    if (b.primitives.size() > 1) label += "s";
    for (size_t i = 0; i < b.primitives.size(); ++i) {
      label += i ? ',' : ' ';
      label += std::to_string(b.primitives[i]);
    }
    return label;
  }

  void readPositions(GltfPartBinding& b, MeshPart& part) const {
    const auto& posAcc = model_.accessors.at(b.positionAccessor);
    if (componentCount(posAcc.type) != 3) fail(path_, part.label + ": POSITION is not VEC3");
    if (posAcc.count > options_.maxVertices)
      fail(path_, part.label + " POSITION (accessor " + std::to_string(b.positionAccessor) + ") declares " +
                      std::to_string(posAcc.count) + " vertices, more than the limit of " +
                      std::to_string(options_.maxVertices) + " (raise it with --max-vertices)");
    const auto pos = readAccessor(model_, b.positionAccessor, path_, part.label + " POSITION", false, options_.maxVertices);
    b.vertexCount = posAcc.count;
    part.positions.resize(b.vertexCount);
    for (size_t v = 0; v < b.vertexCount; ++v) {
      part.positions[v] = Vec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
      if (!part.positions[v].allFinite())
        fail(path_, part.label + ": vertex " + std::to_string(v) + " has a non-finite position (" +
                        formatNumber(pos[3 * v]) + ", " + formatNumber(pos[3 * v + 1]) + ", " +
                        formatNumber(pos[3 * v + 2]) + ")");
    }
  }

  // The primitive's indices (or 0, 1, 2, ... without them), checked against POSITION.
  void readTriangles(const GltfPartBinding& b, int p, MeshPart& part) const {
    const auto& mesh = model_.meshes[b.mesh];
    const auto& prim = mesh.primitives[p];
    const std::string plabel = "mesh " + std::to_string(b.mesh) + " '" + mesh.name + "' primitive " + std::to_string(p);
    std::vector<double> idx;
    if (prim.indices >= 0) {
      const auto& ia = model_.accessors.at(prim.indices);
      if (componentCount(ia.type) != 1) fail(path_, plabel + ": indices accessor " + std::to_string(prim.indices) + " is not SCALAR");
      if (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(path_, plabel + ": indices accessor " + std::to_string(prim.indices) + " has component type " +
                        std::to_string(ia.componentType) +
                        "; indices must be unsigned byte (5121), unsigned short (5123) or unsigned int (5125)");
      idx = readAccessor(model_, prim.indices, path_, plabel + " indices", false, options_.maxVertices);
    } else {
      idx.resize(b.vertexCount);
      for (size_t v = 0; v < b.vertexCount; ++v) idx[v] = static_cast<double>(v);
    }
    if (idx.size() % 3 != 0)
      warnings_.push_back(path_ + ": " + plabel + ": " + std::to_string(idx.size()) +
                          " indices is not a multiple of 3; the last " + std::to_string(idx.size() % 3) + " ignored");
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
      Face f;
      for (int k = 0; k < 3; ++k) {
        const double i = idx[t + k];
        if (i < 0 || i >= static_cast<double>(b.vertexCount))
          fail(path_, plabel + ": triangle " + std::to_string(t / 3) + " uses index " + formatNumber(i) +
                          " out of range (POSITION has " + std::to_string(b.vertexCount) + " vertices)");
        f[k] = static_cast<int>(i);
      }
      part.faces.push_back(f);
    }
  }

  // The accessor of `semantic` shared by every primitive of the part, -1 without one.
  int attribute(const GltfPartBinding& b, const MeshPart& part, const std::string& semantic) const {
    bool inconsistent = false;
    const int acc = sharedAttribute(model_.meshes[b.mesh], b, semantic, inconsistent);
    if (inconsistent)
      warnings_.push_back(path_ + ": " + part.label + ": primitives sharing POSITION use different " + semantic +
                          " accessors; " + semantic + " not read");
    if (acc >= 0 && model_.accessors.at(acc).count != b.vertexCount)
      fail(path_, part.label + " " + semantic + ": " + std::to_string(model_.accessors[acc].count) + " elements for " +
                      std::to_string(b.vertexCount) + " vertices");
    return acc;
  }

  // NORMAL, COLOR_0 and the float attributes whose names start with '_'.
  void readAttributes(const GltfPartBinding& b, MeshPart& part) const {
    if (const int acc = attribute(b, part, "NORMAL"); acc >= 0) {
      if (componentCount(model_.accessors[acc].type) != 3) fail(path_, part.label + ": NORMAL is not VEC3");
      const auto n = readAccessor(model_, acc, path_, part.label + " NORMAL", false, options_.maxVertices);
      part.normals.resize(b.vertexCount);
      for (size_t v = 0; v < b.vertexCount; ++v) part.normals[v] = Vec3(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
    }
    if (const int acc = attribute(b, part, "COLOR_0"); acc >= 0) {
      const int comps = componentCount(model_.accessors[acc].type);
      if (comps != 3 && comps != 4) fail(path_, part.label + ": COLOR_0 is neither VEC3 nor VEC4");
      // Integer colors are normalized by definition, even when the flag is missing.
      const auto c = readAccessor(model_, acc, path_, part.label + " COLOR_0", true, options_.maxVertices);
      part.colors.resize(b.vertexCount);
      for (size_t v = 0; v < b.vertexCount; ++v)
        part.colors[v] = Eigen::Vector4d(c[comps * v], c[comps * v + 1], c[comps * v + 2], comps == 4 ? c[comps * v + 3] : 1.0);
    }
    for (const auto& [semantic, ignored] : model_.meshes[b.mesh].primitives[b.primitives[0]].attributes) {
      if (semantic.empty() || semantic[0] != '_') continue;
      const int acc = attribute(b, part, semantic);
      if (acc < 0) continue;
      const auto& a = model_.accessors[acc];
      const int dim = componentCount(a.type);
      if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || dim > 4) continue;
      part.extras.push_back({semantic, dim, readAccessor(model_, acc, path_, part.label + " " + semantic, false, options_.maxVertices)});
    }
  }

  // One instance per node drawing the part (its world matrix), the identity when none does.
  void placeInstances(const GltfPartBinding& b, MeshPart& part) {
    const std::string limit = worldLimit_ == options_.maxVertices ? ", the limit (raise it with --max-vertices)"
                                                                  : ", more than a mesh can index (2^31 - 1)";
    for (int n : nodesOfMesh_[b.mesh]) {
      if (b.vertexCount > worldLimit_ - worldVertices_)
        fail(path_, "node " + std::to_string(n) + " draws " + part.label + " (" + std::to_string(b.vertexCount) +
                        " vertices) once more: with it the nodes draw more than " + std::to_string(worldLimit_) +
                        " vertices in world space" + limit);
      worldVertices_ += b.vertexCount;
      part.instances.push_back(world_[n]);
    }
    if (part.instances.empty()) {
      if (b.vertexCount > worldLimit_ - worldVertices_)
        fail(path_, part.label + " (" + std::to_string(b.vertexCount) + " vertices) and the parts before it make more than " +
                        std::to_string(worldLimit_) + " vertices" + limit);
      worldVertices_ += b.vertexCount;
      part.instances.push_back(Eigen::Matrix4d::Identity());
    }
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  const ReadOptions& options_;
  std::vector<std::string>& warnings_;
  const std::vector<Eigen::Matrix4d> world_;
  std::vector<std::vector<int>> nodesOfMesh_;
  const size_t worldLimit_;
  size_t worldVertices_ = 0;
};

}  // namespace

Document readGltf(const std::string& path, FileFormat format, const ReadOptions& options) {
  const std::string bytes = readWholeFile(path);
  const bool binary = checkFileHead(path, bytes, format);
  auto source = std::make_shared<DocumentSource>();
  source->format = format;
  GltfSource& g = source->gltf;
  g.baseDir = std::filesystem::path(path).parent_path().string();
  Document doc;
  doc.path = path;
  doc.format = format;
  loadModel(path, bytes, binary, g, doc.warnings);
  // World matrices first: a cycle of nodes is refused before anything else of the scene is read.
  PartReader reader(path, g.model, options, doc.warnings);
  bindParts(path, g, doc.warnings);
  for (GltfPartBinding& b : g.parts) doc.parts.push_back(reader.read(b));

  size_t triangles = 0;
  for (const auto& p : doc.parts) triangles += p.faces.size();
  if (triangles == 0) fail(path, "the file contains no triangles");
  doc.source = std::move(source);
  return doc;
}

}  // namespace geoshift::io

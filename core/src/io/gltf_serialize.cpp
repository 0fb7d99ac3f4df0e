// Serialising a tinygltf model ourselves around tinygltf's JSON writer: tinygltf would write
// buffers and images straight to disk (not atomically, and next to the wrong file); here buffers
// become the GLB BIN chunk, a .bin beside the output or a data URI, and images keep their bytes.
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io_detail.hpp"

namespace geoshift::io {
namespace fs = std::filesystem;
namespace {

std::string base64(const unsigned char* data, size_t n) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (size_t i = 0; i < n; i += 3) {
    const uint32_t b = (uint32_t(data[i]) << 16) | (i + 1 < n ? uint32_t(data[i + 1]) << 8 : 0) |
                       (i + 2 < n ? uint32_t(data[i + 2]) : 0);
    out += abc[(b >> 18) & 63];
    out += abc[(b >> 12) & 63];
    out += i + 1 < n ? abc[(b >> 6) & 63] : '=';
    out += i + 2 < n ? abc[b & 63] : '=';
  }
  return out;
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

std::string sniffMime(const std::vector<unsigned char>& b) {
  if (b.size() >= 4 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return "image/png";
  if (b.size() >= 2 && b[0] == 0xFF && b[1] == 0xD8) return "image/jpeg";
  return "application/octet-stream";
}

// Images are written as they were read: external URI kept, embedded bytes re-embedded unchanged.
bool keepImage(const std::string*, const std::string*, const tinygltf::Image* image, bool,
               std::string* outUri, void*) {
  if (!image->uri.empty()) {
    *outUri = image->uri;
    return true;
  }
  if (image->image.empty()) return false;
  const std::string mime = image->mimeType.empty() ? sniffMime(image->image) : image->mimeType;
  *outUri = "data:" + mime + ";base64," + base64(image->image.data(), image->image.size());
  return true;
}

std::string urlDecode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

bool sameDirectory(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  const bool same = fs::equivalent(a.empty() ? "." : a, b.empty() ? "." : b, ec);
  return !ec && same;
}

}  // namespace

std::vector<std::string> serializeGltf(tinygltf::Model model, const std::string& sourceBaseDir,
                                       const std::string& path, FileFormat format,
                                       AtomicFileSet& files) {
  std::vector<std::string> warnings;
  const fs::path out(path);
  const fs::path outDir = out.parent_path();
  const std::string stem = out.stem().string();
  const bool glb = format == FileFormat::Glb;

  // Buffers that end up outside the JSON are taken out of the model so that tinygltf does not
  // base64 them; their JSON entries are patched below.
  enum class Dest { Bin, File, DataUri };
  std::vector<Dest> dest(model.buffers.size());
  std::vector<std::vector<unsigned char>> taken(model.buffers.size());
  std::vector<std::string> fileNames(model.buffers.size());
  int externalCount = 0;
  for (size_t i = 0; i < model.buffers.size(); ++i) {
    auto& b = model.buffers[i];
    if (glb) dest[i] = i == 0 ? Dest::Bin : Dest::DataUri;
    else dest[i] = isDataUri(b.uri) ? Dest::DataUri : Dest::File;
    if (dest[i] == Dest::DataUri) {
      b.uri.clear();  // tinygltf re-encodes the current data
      continue;
    }
    taken[i] = std::move(b.data);
    b.data.clear();
    b.uri.clear();
    if (dest[i] == Dest::File) {
      // Named after the output, never after the source: writing elsewhere must not touch the
      // input's .bin.
      fileNames[i] = stem + (externalCount ? "_" + std::to_string(externalCount) : "") + ".bin";
      ++externalCount;
    }
  }

  // External images: the output refers to them by the same relative URI, so copy them along
  // when the output goes to another directory.
  const bool otherDir = !sourceBaseDir.empty() && !sameDirectory(sourceBaseDir, outDir);
  for (const auto& img : model.images) {
    if (img.uri.empty() || isDataUri(img.uri) || !otherDir) continue;
    const std::string rel = urlDecode(img.uri);
    const fs::path from = fs::path(sourceBaseDir) / rel;
    std::error_code ec;
    if (fs::path(rel).is_absolute() || !fs::exists(from, ec)) {
      warnings.push_back(path + ": image '" + img.uri + "' not found beside the source; not copied");
      continue;
    }
    files.add((outDir / rel).string(),
              img.image.empty() ? readWholeFile(from.string())
                                : std::string(img.image.begin(), img.image.end()));
  }

  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(keepImage, nullptr);
  std::ostringstream text;
  if (!writer.WriteGltfSceneToStream(&model, text, false, false))
    fail(path, "tinygltf could not serialise the model");
  auto json = nlohmann::json::parse(text.str());
  for (size_t i = 0; i < model.buffers.size(); ++i) {
    if (dest[i] == Dest::DataUri) continue;
    auto& b = json["buffers"][i];
    b["byteLength"] = taken[i].size();
    if (dest[i] == Dest::Bin) {
      b.erase("uri");
    } else {
      b["uri"] = fileNames[i];
      files.add((outDir / fileNames[i]).string(), std::string(taken[i].begin(), taken[i].end()));
    }
  }

  if (!glb) {
    files.add(path, json.dump(2) + "\n");
    return warnings;
  }
  std::string chunkJson = json.dump();
  chunkJson.resize((chunkJson.size() + 3) / 4 * 4, ' ');
  std::string bin = taken.empty() ? std::string() : std::string(taken[0].begin(), taken[0].end());
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  std::string glbBytes;
  auto u32 = [&](uint32_t v) {  // GLB is little-endian
    for (int k = 0; k < 4; ++k) glbBytes += static_cast<char>((v >> (8 * k)) & 0xFF);
  };
  const size_t total = 12 + 8 + chunkJson.size() + (bin.empty() ? 0 : 8 + bin.size());
  glbBytes += "glTF";
  u32(2);
  u32(static_cast<uint32_t>(total));
  u32(static_cast<uint32_t>(chunkJson.size()));
  u32(0x4E4F534A);  // "JSON"
  glbBytes += chunkJson;
  if (!bin.empty()) {
    u32(static_cast<uint32_t>(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    glbBytes += bin;
  }
  files.add(path, std::move(glbBytes));
  return warnings;
}

}  // namespace geoshift::io

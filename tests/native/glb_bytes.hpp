#pragma once
// A GLB file's bytes from a glTF JSON and a BIN chunk, for tests that need exact, tiny files.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace geoshift::test {

inline void putLittle32(std::string& s, uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

// GLB 2.0: 12-byte header, JSON chunk padded with spaces, BIN chunk (if any) padded with zeros.
inline std::string glbBytes(const nlohmann::json& j, std::string bin) {
  std::string text = j.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string out = "glTF";
  putLittle32(out, 2);
  putLittle32(out, static_cast<uint32_t>(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
  putLittle32(out, static_cast<uint32_t>(text.size()));
  out += "JSON";
  out += text;
  if (!bin.empty()) {
    putLittle32(out, static_cast<uint32_t>(bin.size()));
    out.append("BIN\0", 4);
    out += bin;
  }
  return out;
}

}  // namespace geoshift::test

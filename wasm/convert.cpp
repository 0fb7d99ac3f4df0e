#include "convert.hpp"

#include <climits>
#include <cstdint>

#include "geoshift/error.hpp"

namespace geoshift::wasm {

using emscripten::val;

val failure(const std::string& message) {
  val result = val::object();
  result.set("ok", false);
  result.set("error", message);
  return result;
}

bool isA(const val& value, const char* type) { return value.instanceof(val::global(type)); }

val floatsOut(const std::vector<double>& values) {
  return copyOut("Float32Array", std::vector<float>(values.begin(), values.end()));
}

TriangleSoup readSoup(const val& positions, const val& indices) {
  if (!isA(positions, "Float32Array")) throw InputError("positions must be a Float32Array");
  if (!isA(indices, "Uint32Array")) throw InputError("indices must be a Uint32Array");
  const auto positionCount = positions["length"].as<std::size_t>();
  const auto indexCount = indices["length"].as<std::size_t>();
  if (positionCount % 3 != 0) {
    throw InputError("positions holds " + std::to_string(positionCount) +
                     " numbers, not a multiple of 3 (x, y, z per vertex)");
  }
  if (indexCount % 3 != 0) {
    throw InputError("indices holds " + std::to_string(indexCount) +
                     " numbers, not a multiple of 3 (one triple per triangle)");
  }
  const std::vector<float> xyz = emscripten::convertJSArrayToNumberVector<float>(positions);
  const std::vector<std::uint32_t> corners = emscripten::convertJSArrayToNumberVector<std::uint32_t>(indices);

  TriangleSoup soup;
  soup.positions.reserve(xyz.size() / 3);
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) soup.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  soup.faces.reserve(corners.size() / 3);
  for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
    Face face;
    for (int k = 0; k < 3; ++k) {
      // The core takes int indices; a uint32 above INT_MAX would wrap to a negative number and
      // make its message confusing, so it is reported here in the core's words.
      const std::uint32_t index = corners[i + k];
      if (index > static_cast<std::uint32_t>(INT_MAX)) {
        throw InputError("face " + std::to_string(i / 3) + ", corner " + std::to_string(k) +
                         ": vertex index " + std::to_string(index) + " is out of range (" +
                         std::to_string(soup.positions.size()) + " vertices)");
      }
      face[k] = static_cast<int>(index);
    }
    soup.faces.push_back(face);
  }
  return soup;
}

std::vector<double> readFloats(const val& array, std::size_t count, const std::string& what) {
  if (!isA(array, "Float32Array")) throw InputError(what + " must be a Float32Array");
  const auto length = array["length"].as<std::size_t>();
  if (length != count) {
    throw InputError(what + " holds " + std::to_string(length) + " numbers, expected " + std::to_string(count));
  }
  return emscripten::convertJSArrayToNumberVector<double>(array);
}

val reportToJs(const BuildReport& report) {
  val r = val::object();
  r.set("inputVertices", report.inputVertices);
  r.set("inputFaces", report.inputFaces);
  r.set("weldedVertices", report.weldedVertices);
  r.set("repeatedIndexFaces", report.repeatedIndexFaces);
  r.set("zeroAreaFaces", report.zeroAreaFaces);
  r.set("reorientedFaces", report.reorientedFaces);
  r.set("nonManifoldEdges", report.nonManifoldEdges);
  r.set("nonManifoldVertices", report.nonManifoldVertices);
  r.set("splitVertexCopies", report.splitVertexCopies);
  r.set("isolatedVertices", report.isolatedVertices);
  val messages = val::array();
  for (const std::string& m : report.messages) messages.call<void>("push", m);
  r.set("messages", messages);
  return r;
}

}  // namespace geoshift::wasm

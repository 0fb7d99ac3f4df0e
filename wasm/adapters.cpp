#include "adapters.hpp"

#include <climits>
#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include <emscripten/val.h>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/mesh.hpp"

namespace geoshift::wasm {
namespace {

using emscripten::val;

val failure(const std::string& message) {
  val result = val::object();
  result.set("ok", false);
  result.set("error", message);
  return result;
}

// `new Float32Array(view)` copies, and the view into the heap dies with this expression: JS never
// holds a view that a later memory growth would detach.
template <class T>
val copyOut(const char* arrayType, const std::vector<T>& values) {
  return val::global(arrayType).new_(emscripten::typed_memory_view(values.size(), values.data()));
}

// The core computes in double; the boundary carries float like the GL buffers it feeds.
val perCallerFloats(const std::vector<double>& meshValues, const std::vector<int>& vertexOf) {
  const std::vector<double> caller = toCallerLayout(meshValues, 1, vertexOf);
  return copyOut("Float32Array", std::vector<float>(caller.begin(), caller.end()));
}

// Checked here rather than in the core because a wrong array type would otherwise be converted
// silently (a plain Array of strings, a Float64Array of indices).
bool isA(const val& value, const char* type) { return value.instanceof(val::global(type)); }

TriangleSoup readSoup(const val& positions, const val& indices) {
  const std::vector<float> xyz = emscripten::convertJSArrayToNumberVector<float>(positions);
  const std::vector<std::uint32_t> corners =
      emscripten::convertJSArrayToNumberVector<std::uint32_t>(indices);

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

val reportToJs(const BuildReport& report) {
  val r = val::object();
  r.set("inputVertices", report.inputVertices);
  r.set("inputFaces", report.inputFaces);
  r.set("weldedVertices", report.weldedVertices);
  r.set("repeatedIndexFaces", report.repeatedIndexFaces);
  r.set("zeroAreaFaces", report.zeroAreaFaces);
  r.set("nonManifoldEdges", report.nonManifoldEdges);
  r.set("nonManifoldVertices", report.nonManifoldVertices);
  r.set("splitVertexCopies", report.splitVertexCopies);
  r.set("isolatedVertices", report.isolatedVertices);
  val messages = val::array();
  for (const std::string& m : report.messages) messages.call<void>("push", m);
  r.set("messages", messages);
  return r;
}

val processMeshChecked(const val& positions, const val& indices) {
  if (!isA(positions, "Float32Array")) return failure("positions must be a Float32Array");
  if (!isA(indices, "Uint32Array")) return failure("indices must be a Uint32Array");
  const auto positionCount = positions["length"].as<std::size_t>();
  const auto indexCount = indices["length"].as<std::size_t>();
  if (positionCount % 3 != 0) {
    return failure("positions holds " + std::to_string(positionCount) +
                   " numbers, not a multiple of 3 (x, y, z per vertex)");
  }
  if (indexCount % 3 != 0) {
    return failure("indices holds " + std::to_string(indexCount) +
                   " numbers, not a multiple of 3 (one triple per triangle)");
  }

  const MeshBuild build = buildMesh(readSoup(positions, indices));
  const Curvatures curvature = curvatures(build.mesh);
  std::vector<double> absolute(curvature.mean.size());
  for (std::size_t v = 0; v < absolute.size(); ++v) absolute[v] = curvature.absolute(static_cast<int>(v));

  val result = val::object();
  result.set("ok", true);
  result.set("weldedVertexCount", build.mesh.vertexCount());
  result.set("faceCount", build.mesh.faceCount());
  result.set("vertexOf", copyOut("Int32Array", build.vertexOf));
  result.set("report", reportToJs(build.report));
  result.set("averageEdgeLength", averageEdgeLength(build.mesh));
  result.set("meanCurvature", perCallerFloats(curvature.mean, build.vertexOf));
  result.set("gaussianCurvature", perCallerFloats(curvature.gaussian, build.vertexOf));
  result.set("absoluteCurvature", perCallerFloats(absolute, build.vertexOf));
  return result;
}

}  // namespace

val processMesh(const val& positions, const val& indices) {
  try {
    return processMeshChecked(positions, indices);
  } catch (const InputError& e) {
    return failure(e.what());
  } catch (const std::bad_alloc&) {
    return failure("out of memory: the mesh is too large for the 4 GB WebAssembly heap");
  } catch (const std::exception& e) {
    return failure(std::string("internal error: ") + e.what());
  } catch (...) {
    return failure("internal error: unknown exception");
  }
}

}  // namespace geoshift::wasm

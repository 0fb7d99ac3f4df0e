#include "adapters.hpp"

#include <vector>

#include "convert.hpp"
#include "geoshift/curvature.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/mesh.hpp"

namespace geoshift::wasm {

using emscripten::val;

val processMesh(const val& positions, const val& indices) {
  return guarded([&] {
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
    result.set("meanCurvature", floatsOut(toCallerLayout(curvature.mean, 1, build.vertexOf)));
    result.set("gaussianCurvature", floatsOut(toCallerLayout(curvature.gaussian, 1, build.vertexOf)));
    result.set("absoluteCurvature", floatsOut(toCallerLayout(absolute, 1, build.vertexOf)));
    return result;
  });
}

}  // namespace geoshift::wasm

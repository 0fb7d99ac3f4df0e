// op "geodesic": geodesic distance from one vertex (DGPC log map) as the scalar "_GEODESIC";
// vertices beyond the radius get -1 so a color map can show them as "not reached".
#include <cstdint>
#include <limits>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/geometry.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runGeodesic(const OpContext& context) {
  const Session& s = context.session;
  const std::int64_t given = context.params.integer64("source");
  requireIndex("geodesic: parameter source", given, s.callerVertexCount());
  const int source = static_cast<int>(given);
  // In multiples of the average edge length; without one, no limit: every vertex connected to the source.
  const double radius = context.params.optionalNumber("radius").value_or(std::numeric_limits<double>::infinity());
  const Mesh& mesh = s.build.mesh;
  const int vertex = s.build.vertexOf[source];
  if (mesh.isIsolated(vertex)) throw InputError("geodesic: source vertex " + std::to_string(source) + " belongs to no triangle");

  context.progress.step(0, "geodesic distance");
  const SurfaceGeometry geometry(mesh);
  LogMap solver(geometry);
  std::vector<double> distance(mesh.vertexCount(), -1.0);
  int reached = 0;
  for (const LogMapEntry& e : solver.computeFromVertex(vertex, radius * averageEdgeLength(mesh))) {
    distance[e.vertex] = e.distance;
    ++reached;
  }
  OpOutput out;
  out.scalars.emplace_back("_GEODESIC", std::move(distance));
  out.stats.set("reachedVertices", reached);
  return out;
}

}  // namespace geoshift::wasm

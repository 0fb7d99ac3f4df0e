// op "geodesic": geodesic distance from one vertex (DGPC log map) as the scalar "_GEODESIC";
// vertices beyond the radius get -1 so a color map can show them as "not reached".
#include <limits>

#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/geometry.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

OpOutput runGeodesic(const OpContext& context) {
  const Session& s = context.session;
  const int source = context.params.integer("source", 0, 0, s.callerVertexCount() - 1);
  // In multiples of the average edge length; the default reaches any vertex of a sane mesh.
  const double radius = context.params.number("radius", 1e9, 1e-6, 1e12);
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

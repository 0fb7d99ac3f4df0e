// Geodesic inspection commands: geodesic (distance field into a file), logmap (CSV), expmap (end
// point). Vertex and face numbers are the file's own (0-based); lengths are in multiples of the
// average edge length (AEL) unless --absolute is given, for input and output alike, so the x,y that
// logmap prints can be fed to expmap --vector as they are.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "geoshift/curvature.hpp"
#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"

namespace geoshift::cli {
namespace {

struct Source {
  std::string file;
  int part = 0;
  bool absolute = false;
  std::optional<int> vertex;
  std::optional<int> face;
  std::vector<double> bary;
};

void addSourceOptions(CLI::App* sub, Source& s, bool vertexOnly) {
  sub->add_option("IN", s.file, "mesh file (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("--part", s.part, "which mesh of the file (0-based, as `geoshift info` lists them)")->capture_default_str();
  sub->add_flag("--absolute", s.absolute, "lengths in the mesh's units instead of multiples of the average edge length");
  if (vertexOnly) {
    sub->add_option("--source", s.vertex, "source vertex (0-based, in the file's order)")->required();
    return;
  }
  auto* v = sub->add_option("--source", s.vertex, "source vertex (0-based, in the file's order)");
  auto* f = sub->add_option("--face", s.face, "source face (0-based, in the file's order)");
  auto* b = sub->add_option("--bary", s.bary, "barycentric coordinates a,b,c of the point in --face")
                ->delimiter(',')->expected(3);
  v->excludes(f);
  f->needs(b);
  b->needs(f);
}

// A file part as a welded mesh, with what the commands need to speak in the file's numbering.
struct Loaded {
  Document doc;
  int partIndex = 0;
  MeshBuild build;
  std::unique_ptr<SurfaceGeometry> geometry;
  double unit = 1.0;  // AEL, or 1 with --absolute

  const Mesh& mesh() const { return build.mesh; }
  MeshPart& part() { return doc.parts[partIndex]; }
  const MeshPart& part() const { return doc.parts[partIndex]; }
  int meshFace(int fileFace) const {
    for (int f = 0; f < mesh().faceCount(); ++f)
      if (mesh().inputFace(f) == fileFace) return f;
    return -1;
  }
};

Loaded loadPart(const Source& s) {
  Loaded l{load(s.file), s.part, {}, nullptr, 1.0};
  if (s.part < 0 || s.part >= static_cast<int>(l.doc.parts.size()))
    throw InputError(s.file + ": part " + std::to_string(s.part) + " does not exist (the file has " +
                     std::to_string(l.doc.parts.size()) + ")");
  l.build = buildPart(l.doc, l.part());
  l.geometry = std::make_unique<SurfaceGeometry>(l.build.mesh);
  l.unit = s.absolute ? 1.0 : l.geometry->averageEdgeLength();
  return l;
}

SurfacePoint sourcePoint(const Source& s, const Loaded& l) {
  const MeshPart& part = l.part();
  if (s.vertex) {
    const int v = *s.vertex;
    if (v < 0 || v >= static_cast<int>(part.positions.size()))
      throw InputError(s.file + ": source vertex " + std::to_string(v) + " is out of range (" +
                       std::to_string(part.positions.size()) + " vertices in " + part.label + ")");
    const int mv = l.build.vertexOf[v];
    if (l.mesh().isIsolated(mv))
      throw InputError(s.file + ": source vertex " + std::to_string(v) + " is isolated: no face uses it");
    return SurfacePoint::atVertex(l.mesh(), mv);
  }
  if (!s.face) throw InputError("give a source: --source V, or --face F --bary a,b,c");
  const int f = *s.face;
  if (f < 0 || f >= static_cast<int>(part.faces.size()))
    throw InputError(s.file + ": face " + std::to_string(f) + " is out of range (" + std::to_string(part.faces.size()) +
                     " faces in " + part.label + ")");
  const int mf = l.meshFace(f);
  if (mf < 0) throw InputError(s.file + ": face " + std::to_string(f) + " is degenerate and was dropped");
  return SurfacePoint::inFace(l.mesh(), mf, l.mesh().inputCornerOrder(mf, Vec3(s.bary[0], s.bary[1], s.bary[2])));
}

// Enough to reach every vertex: no geodesic is longer than all edges laid end to end.
double wholeMeshRadius(const SurfaceGeometry& g) {
  double sum = 0;
  for (int h = 0; h < g.mesh().halfedgeCount(); ++h) sum += g.length(h);
  return sum;
}

double radiusOf(const std::optional<double>& radius, const Loaded& l) {
  if (!radius) return wholeMeshRadius(*l.geometry);
  requirePositive("--radius", *radius);
  return *radius * l.unit;
}

}  // namespace

Command addGeodesic(CLI::App& app) {
  struct Args : Source {
    std::string out;
    std::optional<double> radius;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "geodesic", "Geodesic distance and angle from a vertex (log map), as a color-mapped COLOR_0 and the attributes "
                  "_GEODESIC_DISTANCE and _GEODESIC_ANGLE");
  addSourceOptions(sub, *a, true);
  sub->add_option("-o,--output", a->out, "output mesh; format from its extension")->required();
  sub->add_option("--radius", a->radius, "stop at this geodesic distance (default: the whole mesh)");
  return {sub, [a] {
            Loaded l = loadPart(*a);
            const SurfacePoint source = sourcePoint(*a, l);
            LogMap solver(*l.geometry);
            const auto& entries = solver.compute(source, radiusOf(a->radius, l));
            // Vertices beyond the radius get -1 (distance) and 0 (angle), and a neutral grey.
            const int n = l.mesh().vertexCount();
            std::vector<double> distance(n, -1.0), angle(n, 0.0);
            for (const LogMapEntry& e : entries) {
              distance[e.vertex] = e.distance / l.unit;
              angle[e.vertex] = e.angle;
            }
            std::vector<double> reached;
            for (double d : distance)
              if (d >= 0) reached.push_back(d);
            const std::vector<double> rgb = colorMap(reached);
            std::vector<double> colors(static_cast<size_t>(n) * 3, 0.5);
            for (int v = 0, i = 0; v < n; ++v)
              if (distance[v] >= 0) {
                std::copy_n(&rgb[3 * i], 3, &colors[3 * v]);
                ++i;
              }
            MeshPart& part = l.part();
            const auto& vertexOf = l.build.vertexOf;
            const auto callerColors = toCallerLayout(colors, 3, vertexOf);
            part.colors.resize(part.positions.size());
            for (size_t i = 0; i < part.colors.size(); ++i)
              part.colors[i] = {callerColors[3 * i], callerColors[3 * i + 1], callerColors[3 * i + 2], 1.0};
            std::erase_if(part.extras, [](const ExtraAttribute& e) { return e.name.starts_with("_GEODESIC_"); });
            part.extras.push_back({"_GEODESIC_DISTANCE", 1, toCallerLayout(distance, 1, vertexOf)});
            part.extras.push_back({"_GEODESIC_ANGLE", 1, toCallerLayout(angle, 1, vertexOf)});
            save(l.doc, a->out);
            std::fprintf(stderr, "geoshift: %zu of %d vertices within the radius\n", entries.size(), n);
          }};
}

Command addLogMap(CLI::App& app) {
  struct Args : Source {
    double radius = 0;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "logmap", "Geodesic polar coordinates of every vertex within a radius, as CSV: vertex,u,theta,x,y");
  addSourceOptions(sub, *a, false);
  sub->add_option("--radius", a->radius, "geodesic radius")->required();
  return {sub, [a] {
            const Loaded l = loadPart(*a);
            const SurfacePoint source = sourcePoint(*a, l);
            LogMap solver(*l.geometry);
            const auto& entries = solver.compute(source, radiusOf(a->radius, l));
            // Mesh vertex -> the file's vertices welded into it, so every file vertex gets its row.
            std::vector<std::vector<int>> fileVertices(l.mesh().vertexCount());
            for (size_t i = 0; i < l.build.vertexOf.size(); ++i) fileVertices[l.build.vertexOf[i]].push_back(static_cast<int>(i));
            std::printf("vertex,u,theta,x,y\n");
            for (const LogMapEntry& e : entries) {
              const Vec2 xy = e.coords() / l.unit;
              for (int fv : fileVertices[e.vertex])
                std::printf("%d,%.17g,%.17g,%.17g,%.17g\n", fv, e.distance / l.unit, e.angle, xy.x(), xy.y());
            }
          }};
}

Command addExpMap(CLI::App& app) {
  struct Args : Source {
    std::vector<double> vector, toward;
    std::optional<double> length;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "expmap", "Walk a straightest geodesic from a surface point and print where it ends");
  addSourceOptions(sub, *a, false);
  auto* vec = sub->add_option("--vector", a->vector, "tangent vector x,y in the frame of the start point (the frame "
                                                     "logmap prints); write --vector=-1,2 for negative values")
                  ->delimiter(',')->expected(2);
  auto* toward = sub->add_option("--toward", a->toward, "start direction dx,dy,dz in 3D, projected onto the start face")
                     ->delimiter(',')->expected(3);
  auto* length = sub->add_option("--length", a->length, "length of the walk with --toward");
  vec->excludes(toward);
  toward->needs(length);
  length->needs(toward);
  sub->add_flag("--json", a->json, R"(print one JSON object {"face", "bary", "point", "hitBoundary"})");
  return {sub, [a] {
            const Loaded l = loadPart(*a);
            const SurfacePoint start = sourcePoint(*a, l);
            Vec2 v;
            if (!a->vector.empty()) {
              v = Vec2(a->vector[0], a->vector[1]) * l.unit;
            } else if (!a->toward.empty()) {
              const Vec2 dir = tangentFromDirection(*l.geometry, start, Vec3(a->toward[0], a->toward[1], a->toward[2]));
              if (!(dir.norm() > 0)) throw InputError("--toward is perpendicular to the start face: no direction to walk");
              v = dir.normalized() * (*a->length * l.unit);
            } else {
              throw InputError("give a direction: --vector x,y, or --toward dx,dy,dz --length L");
            }
            if (!v.allFinite()) throw InputError("the vector must be finite");
            const ExpMapResult r = expMap(*l.geometry, start, v);
            const int face = l.mesh().inputFace(r.end.face);
            const Vec3 bary = l.mesh().inputCornerOrder(r.end.face, Vec3(r.end.bary[0], r.end.bary[1], r.end.bary[2]));
            const Vec3 p = r.end.position(l.mesh());
            if (a->json) {
              const nlohmann::ordered_json j = {{"face", face},
                                        {"bary", {bary[0], bary[1], bary[2]}},
                                        {"point", {p.x(), p.y(), p.z()}},
                                        {"hitBoundary", r.hitBoundary}};
              std::printf("%s\n", j.dump().c_str());
              return;
            }
            std::printf("face %d bary %.17g %.17g %.17g\npoint %.17g %.17g %.17g\nhitBoundary %s\nlength %.17g\n", face,
                        bary[0], bary[1], bary[2], p.x(), p.y(), p.z(),
                        r.hitBoundary ? "true" : "false", r.length / l.unit);
          }};
}

}  // namespace geoshift::cli

// Geodesics of a mesh in the caller's numbering, as `geoshift logmap / expmap / geodesic` speak
// (cli/geodesic.cpp): lengths in multiples of the AEL unless absolute.
#include <mutex>

#include "bindings.hpp"
#include "geoshift/geodesic.hpp"

namespace geoshift::python {

namespace {

struct Geodesics {
  std::shared_ptr<Built> built;
  std::unique_ptr<LogMap> solver;
  std::vector<int> meshFaceOf;                  // caller face -> mesh face (-1: dropped)
  std::vector<std::vector<int>> callerVertices;  // mesh vertex -> the caller's vertices welded into it
  std::mutex busy;                               // one call at a time (the solver keeps buffers)

  explicit Geodesics(std::shared_ptr<Built> b) : built(std::move(b)) {
    const Mesh& mesh = built->mesh();
    solver = std::make_unique<LogMap>(built->surface());
    int inputFaces = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) inputFaces = std::max(inputFaces, mesh.inputFace(f) + 1);
    inputFaces = std::max(inputFaces, built->build.report.inputFaces);
    meshFaceOf.assign(inputFaces, -1);
    for (int f = 0; f < mesh.faceCount(); ++f) meshFaceOf[mesh.inputFace(f)] = f;
    callerVertices.resize(mesh.vertexCount());
    for (size_t i = 0; i < built->build.vertexOf.size(); ++i) callerVertices[built->build.vertexOf[i]].push_back(static_cast<int>(i));
  }

  double unit(bool absolute) { return absolute ? 1.0 : built->surface().averageEdgeLength(); }

  // A vertex (int) or (face, (a, b, c)) in the caller's numbering as a surface point.
  SurfacePoint point(const py::handle& source) const {
    const Mesh& mesh = built->mesh();
    if (py::isinstance<py::int_>(source)) {
      const long v = source.cast<long>();
      if (v < 0 || v >= built->callerVertices())
        throw InputError("source vertex " + std::to_string(v) + " is out of range (" + std::to_string(built->callerVertices()) + " vertices)");
      const int mv = built->build.vertexOf[v];
      if (mesh.isIsolated(mv)) throw InputError("source vertex " + std::to_string(v) + " is isolated: no face uses it");
      return SurfacePoint::atVertex(mesh, mv);
    }
    py::sequence s;
    try {
      s = source.cast<py::sequence>();
    } catch (const py::cast_error&) {
      throw InputError("a source is a vertex index or (face, (a, b, c))");
    }
    if (s.size() != 2) throw InputError("a source is a vertex index or (face, (a, b, c))");
    const long f = s[0].cast<long>();
    const std::vector<double> bary = s[1].cast<std::vector<double>>();
    if (bary.size() != 3) throw InputError("barycentric coordinates are three numbers");
    if (f < 0 || f >= static_cast<long>(meshFaceOf.size()))
      throw InputError("face " + std::to_string(f) + " is out of range (" + std::to_string(meshFaceOf.size()) + " faces)");
    const int mf = meshFaceOf[f];
    if (mf < 0) throw InputError("face " + std::to_string(f) + " is degenerate and was dropped");
    return SurfacePoint::inFace(mesh, mf, mesh.inputCornerOrder(mf, Vec3(bary[0], bary[1], bary[2])));
  }
};

}  // namespace

void bindGeodesics(py::module_& m) {
  py::class_<Geodesics>(m, "_Geodesics")
      .def(py::init([](std::shared_ptr<Built> b) { return std::make_unique<Geodesics>(std::move(b)); }))
      .def_property_readonly("average_edge_length", [](Geodesics& g) { return g.unit(false); })
      .def("log_map", [](Geodesics& g, const py::handle& source, double radius, bool absolute) {
        const SurfacePoint p = g.point(source);
        const double unit = g.unit(absolute);
        if (!(radius > 0)) throw InputError("radius must be positive");
        Run run;
        std::vector<int> vertex;
        std::vector<double> u, theta, x, y;
        run([&](const Progress&) {
          std::lock_guard lock(g.busy);
          for (const LogMapEntry& e : g.solver->compute(p, radius * unit)) {
            const Vec2 xy = e.coords() / unit;
            for (int fv : g.callerVertices[e.vertex]) {
              vertex.push_back(fv);
              u.push_back(e.distance / unit);
              theta.push_back(e.angle);
              x.push_back(xy.x());
              y.push_back(xy.y());
            }
          }
          return 0;
        });
        py::dict out;
        out["vertex"] = fromVector(vertex);
        out["distance"] = fromVector(u);
        out["angle"] = fromVector(theta);
        out["x"] = fromVector(x);
        out["y"] = fromVector(y);
        return out;
      }, py::arg("source"), py::arg("radius"), py::arg("absolute") = false)
      .def("exp_map", [](Geodesics& g, const py::handle& start, const py::handle& vector, const py::handle& toward,
                         const py::handle& length, bool absolute, bool recordPath) {
        const SurfacePoint p = g.point(start);
        const double unit = g.unit(absolute);
        Vec2 v;
        if (!vector.is_none()) {
          const auto xy = vector.cast<std::vector<double>>();
          if (xy.size() != 2) throw InputError("vector is two numbers (x, y) in the start point's frame");
          v = Vec2(xy[0], xy[1]) * unit;
        } else if (!toward.is_none()) {
          const auto d = toward.cast<std::vector<double>>();
          if (d.size() != 3) throw InputError("toward is a 3D direction (dx, dy, dz)");
          if (length.is_none()) throw InputError("toward needs a length");
          const Vec2 dir = tangentFromDirection(g.built->surface(), p, Vec3(d[0], d[1], d[2]));
          if (!(dir.norm() > 0)) throw InputError("toward is perpendicular to the start face: no direction to walk");
          v = dir.normalized() * (length.cast<double>() * unit);
        } else {
          throw InputError("give a direction: vector=(x, y), or toward=(dx, dy, dz) and length");
        }
        if (!v.allFinite()) throw InputError("the vector must be finite");
        ExpMapOptions o;
        o.recordPath = recordPath;
        Run run;
        const ExpMapResult r = run([&](const Progress&) { return expMap(g.built->surface(), p, v, o); });
        const Mesh& mesh = g.built->mesh();
        py::dict out;
        out["face"] = mesh.inputFace(r.end.face);
        const Vec3 bary = mesh.inputCornerOrder(r.end.face, Vec3(r.end.bary[0], r.end.bary[1], r.end.bary[2]));
        out["bary"] = py::make_tuple(bary[0], bary[1], bary[2]);
        const Vec3 q = r.end.position(mesh);
        out["point"] = py::make_tuple(q.x(), q.y(), q.z());
        out["hit_boundary"] = r.hitBoundary;
        out["length"] = r.length / unit;
        out["faces_crossed"] = r.facesCrossed;
        if (recordPath) out["path"] = fromPoints(r.path);
        return out;
      }, py::arg("start"), py::arg("vector") = py::none(), py::arg("toward") = py::none(), py::arg("length") = py::none(),
         py::arg("absolute") = false, py::arg("record_path") = false)
      .def("distance_field", [](Geodesics& g, const py::handle& source, double radius, bool absolute) {
        // Per caller vertex: distance (-1 beyond the radius) and polar angle, as `geoshift geodesic` writes.
        const SurfacePoint p = g.point(source);
        const double unit = g.unit(absolute);
        double reach = radius * unit;
        if (radius <= 0) {  // the whole mesh: all edges laid end to end
          reach = 0;
          for (int h = 0; h < g.built->mesh().halfedgeCount(); ++h) reach += g.built->surface().length(h);
        }
        const int n = g.built->mesh().vertexCount();
        std::vector<double> distance(n, -1.0), angle(n, 0.0);
        Run run;
        run([&](const Progress&) {
          std::lock_guard lock(g.busy);
          for (const LogMapEntry& e : g.solver->compute(p, reach)) {
            distance[e.vertex] = e.distance / unit;
            angle[e.vertex] = e.angle;
          }
          return 0;
        });
        return py::make_tuple(fromVector(g.built->toCaller(distance, 1)), fromVector(g.built->toCaller(angle, 1)));
      }, py::arg("source"), py::arg("radius") = 0.0, py::arg("absolute") = false);
}

}  // namespace geoshift::python

// Terrain import: the LAS / PLY point and GeoTIFF readers, the terrain meshes built from them
// (2.5D Delaunay, raster grid), the procedural terrain. Positions stay absolute and z-up.
#include "bindings.hpp"
#include "geoshift/terrain.hpp"
#include "options.hpp"

namespace geoshift::python {

namespace {

py::dict pointsDict(const TerrainPoints& p) {
  py::dict d;
  d["positions"] = fromPoints(p.positions);
  d["classes"] = p.classes.empty() ? py::object(py::none()) : py::object(fromVector(p.classes));
  if (p.colors.empty()) {
    d["colors"] = py::none();
  } else {
    std::vector<double> rgb;
    rgb.reserve(3 * p.colors.size());
    for (const auto& c : p.colors) rgb.insert(rgb.end(), {c[0], c[1], c[2]});
    d["colors"] = fromRows(rgb, 3);
  }
  d["notes"] = p.notes;
  return d;
}

TerrainPoints pointsOf(const py::handle& positions, const py::handle& classes, const py::handle& colors) {
  TerrainPoints p;
  p.positions = toPoints(positions, "points");
  if (!classes.is_none()) {
    int dim = 1;
    for (double c : toRows(classes, "classes", dim)) p.classes.push_back(static_cast<int>(c));
    if (dim != 1) throw InputError("classes must have one value per point");
  }
  if (!colors.is_none()) {
    int dim = 0;
    const std::vector<double> rows = toRows(colors, "colors", dim);
    if (dim != 3) throw InputError("colors must have shape (N, 3)");
    for (size_t i = 0; i + 2 < rows.size(); i += 3) p.colors.emplace_back(rows[i], rows[i + 1], rows[i + 2]);
  }
  return p;
}

// A terrain mesh as the dict a geoshift.Mesh is made from: COLOR_0 becomes the colors, every other
// attribute keeps its name; the report rides along.
py::dict meshDict(const TerrainMesh& t) {
  py::dict d;
  d["label"] = "terrain";
  d["positions"] = fromPoints(t.positions);
  d["faces"] = fromFaces(t.faces);
  d["normals"] = py::none();
  d["colors"] = py::none();
  py::dict attributes;
  for (const Attribute& a : t.attributes.all()) {
    if (a.name == "COLOR_0") {
      std::vector<double> rgba;
      rgba.reserve(4 * a.vertexCount());
      for (int v = 0; v < a.vertexCount(); ++v) rgba.insert(rgba.end(), {a.row(v)[0], a.row(v)[1], a.row(v)[2], 1.0});
      d["colors"] = fromRows(rgba, 4);
    } else {
      attributes[a.name.c_str()] = fromRows(a.values, a.dim);
    }
  }
  d["attributes"] = attributes;
  py::dict report;
  report["points_read"] = t.report.pointsRead;
  report["points_used"] = t.report.pointsUsed;
  report["duplicates_dropped"] = t.report.duplicatesDropped;
  report["nodata_cells"] = t.report.nodataCells;
  report["ground_points"] = t.report.groundPoints;
  report["notes"] = t.report.notes;
  d["report"] = report;
  return d;
}

}  // namespace

void bindTerrain(py::module_& m) {
  m.def("read_las", [](const std::string& path) {
    Run run;
    return pointsDict(run([&](const Progress&) { return readLas(path); }));
  }, py::arg("path"), "LAS 1.0-1.4 points: dict of positions (N, 3), classes (N,) or None, colors (N, 3) in [0, 1] or None, notes.");
  m.def("read_ply_points", [](const std::string& path) {
    Run run;
    return pointsDict(run([&](const Progress&) { return readPlyPoints(path); }));
  }, py::arg("path"), "A PLY point set (vertex x y z, optional colors and class), as read_las.");
  m.def("read_geotiff", [](const std::string& path) {
    Run run;
    const ElevationGrid g = run([&](const Progress&) { return readGeoTiff(path); });
    py::array_t<double> values({static_cast<py::ssize_t>(g.height), static_cast<py::ssize_t>(g.width)});
    std::copy(g.values.begin(), g.values.end(), values.mutable_data());
    py::dict d;
    d["values"] = values;
    d["transform"] = py::make_tuple(g.transform[0], g.transform[1], g.transform[2], g.transform[3], g.transform[4], g.transform[5]);
    d["geographic"] = g.geographic;
    d["notes"] = g.notes;
    return d;
  }, py::arg("path"),
        "A DEM GeoTIFF: dict of values (rows, cols; NaN = nodata), transform (GDAL geotransform, cell centres at +0.5), "
        "geographic, notes.");

  m.def("_read_terrain", [](const std::string& path, bool groundOnly, int groundClass, bool toMeters, const py::object& cb) {
    TerrainReadOptions o;
    o.points.groundOnly = groundOnly;
    o.points.groundClass = groundClass;
    o.grid.geographicToMeters = toMeters;
    Run run(cb);
    return meshDict(run([&](const Progress& p) { return readTerrain(path, o, p); }));
  });
  m.def("_point_terrain", [](const py::handle& positions, const py::handle& classes, const py::handle& colors, bool groundOnly,
                             int groundClass, const py::object& cb) {
    const TerrainPoints points = pointsOf(positions, classes, colors);
    PointTerrainOptions o;
    o.groundOnly = groundOnly;
    o.groundClass = groundClass;
    Run run(cb);
    return meshDict(run([&](const Progress& p) { return pointTerrain(points, o, p); }));
  });
  m.def("_grid_terrain", [](const py::handle& values, const std::vector<double>& transform, bool geographic, bool toMeters,
                            const py::object& cb) {
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
    if (!a || a.ndim() != 2) throw InputError("values must be a 2D array (rows, cols)");
    if (transform.size() != 6) throw InputError("transform must be six numbers (GDAL geotransform)");
    ElevationGrid g;
    g.height = static_cast<int>(a.shape(0));
    g.width = static_cast<int>(a.shape(1));
    g.values.assign(a.data(), a.data() + a.size());
    std::copy(transform.begin(), transform.end(), g.transform.begin());
    g.geographic = geographic;
    GridTerrainOptions o;
    o.geographicToMeters = toMeters;
    Run run(cb);
    return meshDict(run([&](const Progress& p) { return gridTerrain(g, o, p); }));
  });
  m.def("_procedural_terrain", [](const TerrainOptions& o, const py::object& cb) {
    Run run(cb);
    return meshDict(run([&](const Progress& p) { return proceduralTerrain(o, p); }));
  });
  m.def("height_above_ground", [](const py::handle& ground, const py::handle& points) {
    const std::vector<Vec3> g = toPoints(ground, "ground"), q = toPoints(points, "points");
    Run run;
    return fromVector(run([&](const Progress& p) { return heightAboveGround(g, q, p); }));
  }, py::arg("ground"), py::arg("points"),
        "Height of each point above the Delaunay TIN of the ground points (linear along the hull outside it).");
  m.def("delaunay_2d", [](const py::handle& points) {
    const std::vector<Vec3> q = toPoints(points, "points");
    Run run;
    const Delaunay2D d = run([&](const Progress& p) { return delaunay2d(q, {}, p); });
    return py::make_tuple(fromFaces(d.faces), fromVector(d.keptAs));
  }, py::arg("points"), "2.5D Delaunay triangulation of the points' xy: (faces, kept_as), duplicates kept as their first copy.");
}

}  // namespace geoshift::python

// Meshes and files: the welded mesh of a call (_Built), documents read with the core's generic
// reader (every format it reads) and written back with its writer (atomic; the file's own format
// keeps materials, nodes and the rest).
#include "bindings.hpp"

#include "geoshift/geometry.hpp"
#include "geoshift/io.hpp"

namespace geoshift::python {

namespace {

const char* formatName(FileFormat f) {
  switch (f) {
    case FileFormat::Gltf: return "gltf";
    case FileFormat::Glb: return "glb";
    case FileFormat::Obj: return "obj";
    case FileFormat::Off: return "off";
    case FileFormat::Ply: return "ply";
    case FileFormat::Stl: return "stl";
  }
  return "?";
}

// A part of the file as the dict the Python Mesh is made from.
py::dict partDict(const MeshPart& part) {
  py::dict d;
  d["label"] = part.label;
  d["positions"] = fromPoints(part.positions);
  d["faces"] = fromFaces(part.faces);
  d["normals"] = part.normals.empty() ? py::object(py::none()) : py::object(fromPoints(part.normals));
  if (part.colors.empty()) {
    d["colors"] = py::none();
  } else {
    py::array_t<double> c({static_cast<py::ssize_t>(part.colors.size()), py::ssize_t{4}});
    for (size_t i = 0; i < part.colors.size(); ++i)
      for (int k = 0; k < 4; ++k) c.mutable_at(i, k) = part.colors[i][k];
    d["colors"] = c;
  }
  py::array_t<double> inst({static_cast<py::ssize_t>(part.instances.size()), py::ssize_t{4}, py::ssize_t{4}});
  for (size_t i = 0; i < part.instances.size(); ++i)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) inst.mutable_at(i, r, c) = part.instances[i](r, c);
  d["instances"] = inst;
  py::dict attributes;
  for (const ExtraAttribute& e : part.extras) attributes[e.name.c_str()] = fromRows(e.values, e.dim);
  d["attributes"] = attributes;
  return d;
}

}  // namespace

// A Python Mesh (anything with positions, faces and the optional normals, colors, instances,
// attributes, label) as a part to write.
MeshPart partOf(const py::handle& mesh, const std::string& where) {
  MeshPart part;
  part.label = py::hasattr(mesh, "label") && !mesh.attr("label").is_none() ? std::string(py::str(mesh.attr("label"))) : std::string("mesh");
  part.positions = toPoints(mesh.attr("positions"), where + " positions");
  part.faces = toFaces(mesh.attr("faces"), where + " faces");
  const size_t n = part.positions.size();
  const auto optional = [&](const char* name) -> py::object {
    return py::hasattr(mesh, name) ? py::reinterpret_borrow<py::object>(mesh.attr(name)) : py::object(py::none());
  };
  if (py::object normals = optional("normals"); !normals.is_none()) {
    part.normals = toPoints(normals, where + " normals");
    if (part.normals.size() != n)
      throw InputError(where + " has " + std::to_string(part.normals.size()) + " normals for " + std::to_string(n) + " vertices");
  }
  if (py::object colors = optional("colors"); !colors.is_none()) {
    int dim = 0;
    const std::vector<double> rows = toRows(colors, where + " colors", dim);
    if ((dim != 3 && dim != 4) || rows.size() != n * dim)
      throw InputError(where + " colors must have shape (N, 3) or (N, 4) for its " + std::to_string(n) + " vertices");
    part.colors.resize(n);
    for (size_t i = 0; i < n; ++i)
      part.colors[i] = Eigen::Vector4d(rows[dim * i], rows[dim * i + 1], rows[dim * i + 2], dim == 4 ? rows[dim * i + 3] : 1.0);
  }
  if (py::object instances = optional("instances"); !instances.is_none()) {
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(instances);
    if (!a || a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4) throw InputError(where + " instances must have shape (K, 4, 4)");
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
      Eigen::Matrix4d t;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) t(r, c) = a.at(i, r, c);
      part.instances.push_back(t);
    }
  }
  if (part.instances.empty()) part.instances.push_back(Eigen::Matrix4d::Identity());
  if (py::object attributes = optional("attributes"); !attributes.is_none()) {
    for (auto [k, v] : py::cast<py::dict>(attributes)) {
      ExtraAttribute e;
      e.name = py::str(k);
      e.values = toRows(v, where + " attribute '" + e.name + "'", e.dim);
      if (e.values.size() != n * e.dim)
        throw InputError(where + " attribute '" + e.name + "' has " + std::to_string(e.values.size() / e.dim) + " rows for " +
                         std::to_string(n) + " vertices");
      part.extras.push_back(std::move(e));
    }
  }
  return part;
}

void bindMeshIo(py::module_& m) {
  py::class_<Built, std::shared_ptr<Built>>(m, "_Built", "A welded mesh (the core's Mesh) with the map from the caller's vertices.")
      .def_property_readonly("vertex_of", [](const Built& b) { return fromVector(b.build.vertexOf); })
      .def_property_readonly("vertex_count", [](const Built& b) { return b.mesh().vertexCount(); })
      .def_property_readonly("face_count", [](const Built& b) { return b.mesh().faceCount(); })
      .def_property_readonly("positions", [](const Built& b) { return fromPoints(b.mesh().positions()); })
      .def_property_readonly("faces", [](const Built& b) { return fromFaces(b.mesh().faces()); })
      .def_property_readonly("input_face", [](const Built& b) {
        std::vector<int> f(b.mesh().faceCount());
        for (int i = 0; i < b.mesh().faceCount(); ++i) f[i] = b.mesh().inputFace(i);
        return fromVector(f);
      })
      .def_property_readonly("messages", [](const Built& b) { return b.build.report.messages; })
      .def_property_readonly("clean", [](const Built& b) { return b.build.report.clean(); })
      .def_property_readonly("average_edge_length", [](Built& b) { return b.surface().averageEdgeLength(); })
      .def("to_mesh_layout", [](const Built& b, const py::handle& values, bool unit) {
        int dim = 1;
        std::vector<double> rows = toRows(values, "values", dim);
        if (rows.size() != static_cast<size_t>(b.callerVertices()) * dim)
          throw InputError("values have " + std::to_string(rows.size() / dim) + " rows for " + std::to_string(b.callerVertices()) + " vertices");
        return fromRows(b.toMesh(rows, dim, unit), dim);
      }, py::arg("values"), py::arg("unit_vectors") = false)
      .def("to_caller_layout", [](const Built& b, const py::handle& values) {
        int dim = 1;
        std::vector<double> rows = toRows(values, "values", dim);
        if (rows.size() != static_cast<size_t>(b.mesh().vertexCount()) * dim)
          throw InputError("values have " + std::to_string(rows.size() / dim) + " rows for " + std::to_string(b.mesh().vertexCount()) + " mesh vertices");
        return fromRows(b.toCaller(rows, dim), dim);
      });

  m.def("_build", [](const py::handle& positions, const py::handle& faces, bool weld, double tolerance) {
    TriangleSoup soup{toPoints(positions, "positions"), toFaces(faces, "faces")};
    MeshBuildOptions o;
    o.weld = weld;
    o.weldOptions.tolerance = tolerance;
    auto b = std::make_shared<Built>();
    Run run;
    b->build = run([&](const Progress&) { return buildMesh(soup, o); });
    return b;
  }, py::arg("positions"), py::arg("faces"), py::arg("weld") = true, py::arg("tolerance") = 0.0);

  m.def("_read", [](const std::string& path) {
    Run run;
    auto doc = std::make_shared<Document>(run([&](const Progress&) { return readDocument(path); }));
    py::list parts;
    for (const MeshPart& p : doc->parts) parts.append(partDict(p));
    py::dict out;
    out["path"] = doc->path;
    out["format"] = formatName(doc->format);
    out["warnings"] = doc->warnings;
    out["parts"] = parts;
    // The source (tinygltf model, OBJ text) for writing back; the parts' arrays now live in Python.
    for (MeshPart& p : doc->parts) p = MeshPart{};
    out["source"] = py::cast(DocumentHandle{doc});
    return out;
  });

  py::class_<DocumentHandle>(m, "_DocumentSource", "What a file held besides its meshes (kept for writing back).")
      .def(py::pickle([](const DocumentHandle&) -> py::tuple {
             throw py::type_error("a document's source cannot be pickled; send its parts (geoshift.Mesh) instead");
           },
           [](const py::tuple&) -> DocumentHandle { return {}; }));

  m.def("_write", [](const py::handle& source, const std::vector<py::handle>& meshes, const std::string& path) {
    Document doc;
    if (!source.is_none()) {
      const DocumentHandle& h = source.cast<const DocumentHandle&>();
      doc.path = h.document->path;
      doc.format = h.document->format;
      doc.warnings = h.document->warnings;
      doc.source = h.document->source;
    } else {
      doc.path = path;
      doc.format = formatFromPath(path);
    }
    for (size_t i = 0; i < meshes.size(); ++i) doc.parts.push_back(partOf(meshes[i], "part " + std::to_string(i)));
    Run run;
    return run([&](const Progress&) { return writeDocument(doc, path); });
  });

  m.def("_format_of", [](const std::string& path) { return formatName(formatFromPath(path)); });

  m.def("_vertex_normals", [](const py::handle& positions, const py::handle& faces) {
    // On the caller's own faces, unwelded, as the CLI recomputes a part's normals after moving it.
    const MeshBuild own = buildMesh({toPoints(positions, "positions"), toFaces(faces, "faces")}, MeshBuildOptions::withoutWelding());
    const std::vector<Vec3> n = vertexNormals(own.mesh);
    std::vector<Vec3> out(own.vertexOf.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = n[own.vertexOf[i]];
    return fromPoints(out);
  });

  m.def("average_edge_length", [](const py::handle& positions, const py::handle& faces) {
    const MeshBuild b = buildMesh({toPoints(positions, "positions"), toFaces(faces, "faces")});
    return averageEdgeLength(b.mesh);
  }, py::arg("positions"), py::arg("faces"), "Mean length over the edges of the welded mesh: the unit of the spatial options.");
}

}  // namespace geoshift::python

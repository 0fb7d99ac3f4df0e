// Wavelets: an analysis kept with its mesh (geoshift.analyze / Multiresolution.synthesize) and
// `geoshift wavelet` on one part (geoshift.wavelet_filter).
#include <algorithm>

#include "bindings.hpp"
#include "geoshift/wavelet.hpp"
#include "options.hpp"

namespace geoshift::python {

namespace {

// geoshift.analyze and Multiresolution.synthesize.
void bindMultiresolution(py::module_& m) {
  // Wavelets: a Multiresolution of the welded mesh, kept with it.
  struct Analysis {
    std::shared_ptr<Built> built;
    Multiresolution mr;
  };
  py::class_<Analysis, std::shared_ptr<Analysis>>(m, "_Multiresolution")
      .def_property_readonly("vertex_counts", [](const Analysis& a) { return a.mr.vertexCounts(); })
      .def_property_readonly("level_count", [](const Analysis& a) { return a.mr.levelCount(); })
      .def_property_readonly("coarse_positions", [](const Analysis& a) { return fromPoints(a.mr.coarse.positions()); })
      .def_property_readonly("coarse_faces", [](const Analysis& a) { return fromFaces(a.mr.coarse.faces()); })
      .def_property_readonly("coarse_to_mesh", [](const Analysis& a) { return fromVector(a.mr.coarseToFine); })
      .def_property_readonly("cost_bounds", [](const Analysis& a) {
        std::vector<std::vector<double>> bounds;
        for (const WaveletLevel& l : a.mr.levels) bounds.push_back(l.costBounds);
        return bounds;
      })
      .def_property_readonly("coarse_attributes", [](const Analysis& a) {
        py::dict out;
        for (const Attribute& at : a.mr.coarseAttributes.all()) out[at.name.c_str()] = fromRows(at.values, at.dim);
        return out;
      });

  m.def("_analyze", [](std::shared_ptr<Built> b, const py::dict& attributes, const std::vector<std::string>& unit,
                       const WaveletOptions& options, const py::object& callback) {
    const Inputs in = inputsOf(*b, py::none(), attributes, unit);
    AttributeSet set(b->mesh().vertexCount());
    for (const Named& a : in.attributes)
      set.set(a.name, a.dim, a.unit ? AttributeKind::UnitVector : AttributeKind::Euclidean, b->toMesh(a.values, a.dim, a.unit));
    Run run(callback);
    auto a = std::make_shared<Analysis>();
    a->built = b;
    const WaveletOptions w = onMesh(*b, options);
    a->mr = run([&](const Progress& p) { return analyze(b->mesh(), set, w, p); });
    return a;
  });

  m.def("_synthesize", [](const Analysis& a, const py::handle& coarsePositions, const py::handle& coarseAttributes,
                          const std::vector<double>& alpha, const py::object& callback) {
    const Multiresolution& mr = a.mr;
    std::vector<Vec3> positions = coarsePositions.is_none() ? mr.coarse.positions() : toPoints(coarsePositions, "coarse positions");
    AttributeSet attributes = mr.coarseAttributes;
    if (!coarseAttributes.is_none())
      for (auto [k, v] : py::cast<py::dict>(coarseAttributes)) {
        const std::string name = py::str(k);
        const Attribute* old = mr.coarseAttributes.find(name);
        if (!old) throw InputError("the analysis has no attribute '" + name + "'");
        int dim = 1;
        attributes.set(name, old->dim, old->kind, toRows(v, "coarse attribute '" + name + "'", dim));
      }
    Run run(callback);
    const SynthesisResult r = run([&](const Progress& p) { return synthesize(mr, positions, attributes, alpha, p); });
    const Built& b = *a.built;
    std::vector<Vec3> caller(b.callerVertices());
    for (size_t i = 0; i < caller.size(); ++i) caller[i] = r.mesh.position(b.build.vertexOf[i]);
    py::dict out;
    out["positions"] = fromPoints(caller);
    py::dict attrs;
    for (const Attribute& at : r.attributes.all()) attrs[at.name.c_str()] = fromRows(b.toCaller(at.values, at.dim), at.dim);
    out["attributes"] = attrs;
    return out;
  });

}

void bindWaveletFilter(py::module_& m) {
  // `geoshift wavelet` on one part (cli/wavelet.cpp): positions and, unless positionsOnly, the
  // colors' change (clamped to [0, 1]) in the caller's layout.
  m.def("_wavelet_filter", [](Built& b, const py::handle& colors, int levels, const std::vector<double>& alpha,
                              bool positionsOnly, const py::object& callback) {
    const Inputs in = inputsOf(b, colors, py::dict(), {});
    const bool withColors = !in.colors.empty() && !positionsOnly;
    AttributeSet signals(b.mesh().vertexCount());
    std::vector<double> before;
    if (withColors) {
      before = b.toMesh(in.colors, 3);
      signals.set("color", 3, AttributeKind::Euclidean, before);
    }
    WaveletOptions o;
    o.levels = levels;
    Run run(callback);
    Multiresolution mr;
    const SynthesisResult r = run([&](const Progress& p) {
      mr = analyze(b.mesh(), signals, o, p.slice(0, 0.8));
      return synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, alpha, p.slice(0.8, 1));
    });
    py::dict out;
    std::vector<Vec3> positions(b.callerVertices());
    for (size_t i = 0; i < positions.size(); ++i) positions[i] = r.mesh.position(b.build.vertexOf[i]);
    out["positions"] = fromPoints(positions);
    if (withColors) {
      const std::vector<double>& after = r.attributes.get("color").values;
      int dim = 0;
      std::vector<double> rows = toRows(colors, "colors", dim);
      for (size_t i = 0; i < positions.size(); ++i) {
        const int v = b.build.vertexOf[i];
        for (int c = 0; c < 3; ++c) rows[dim * i + c] = std::clamp(rows[dim * i + c] + after[3 * v + c] - before[3 * v + c], 0.0, 1.0);
      }
      out["colors"] = fromRows(rows, dim);
    }
    out["vertex_counts"] = mr.vertexCounts();
    return out;
  });
}

}  // namespace

void bindWavelets(py::module_& m) {
  bindMultiresolution(m);
  bindWaveletFilter(m);
}

}  // namespace geoshift::python

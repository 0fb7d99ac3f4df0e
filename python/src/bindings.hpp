#pragma once
// The module's parts (module.cpp registers them in this order).
#include <memory>

#include "common.hpp"
#include "geoshift/io.hpp"

namespace geoshift::python {

// A read document's source, kept for writing back into the file's own format.
struct DocumentHandle {
  std::shared_ptr<const Document> document;
};

// A Python Mesh as a part to write or filter; InputError naming `where` on bad arrays.
MeshPart partOf(const py::handle& mesh, const std::string& where);

void bindOptions(py::module_& m);
void bindMeshIo(py::module_& m);
void bindFilters(py::module_& m);    // filters.cpp; registers the two below too
void bindDenoising(py::module_& m);  // denoise.cpp
void bindWavelets(py::module_& m);   // wavelets.cpp
void bindGeodesics(py::module_& m);
void bindTerrain(py::module_& m);

}  // namespace geoshift::python

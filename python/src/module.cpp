// geoshift._geoshift: the pybind11 module behind the Python package. The Python layer
// (python/geoshift/*.py) gives it its public names, Mesh and Document classes and docstrings.
#include "bindings.hpp"
#include "options.hpp"

PYBIND11_MODULE(_geoshift, m) {
  using namespace geoshift::python;
  m.doc() = "geoshift core bindings (use the geoshift package)";
  // Bad input: the core's message, which names the file, part, vertex, face or option. A ValueError.
  py::register_exception<geoshift::InputError>(m, "InputError", PyExc_ValueError);
  // A run stopped by its progress callback (returning False); Ctrl-C raises KeyboardInterrupt.
  py::register_exception<geoshift::Cancelled>(m, "Cancelled", PyExc_RuntimeError);
  bindOptions(m);
  bindMeshIo(m);
  bindFilters(m);
  bindGeodesics(m);
  bindTerrain(m);
}

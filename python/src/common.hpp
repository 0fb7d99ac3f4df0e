#pragma once
// What every part of the Python module shares: numpy conversions, the welded mesh a call works on,
// and Run, which executes a core call with the GIL released, forwards its progress to a Python
// callback and turns Ctrl-C (or a callback that raises or returns False) into the core's cancel flag.
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/progress.hpp"
#include "geoshift/wavelet.hpp"

namespace py = pybind11;

namespace geoshift::python {

// --- numpy -------------------------------------------------------------------------------------

// A (N, 3) float array as points; InputError naming `what` on another shape or a non-number dtype.
std::vector<Vec3> toPoints(const py::handle& array, const std::string& what);
// A (M, 3) integer array as faces (indices are checked by the core, which names the face).
std::vector<Face> toFaces(const py::handle& array, const std::string& what);
// (N,) or (N, dim) floats as rows; `dim` receives the row width.
std::vector<double> toRows(const py::handle& array, const std::string& what, int& dim);
// (N,) when dim is 1, else (N, dim).
py::array_t<double> fromRows(const std::vector<double>& values, int dim);
py::array_t<double> fromPoints(const std::vector<Vec3>& points);
py::array_t<int> fromFaces(const std::vector<Face>& faces);
template <class T>
py::array_t<T> fromVector(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// --- the mesh of a call ----------------------------------------------------------------------

// The caller's positions and faces as the core's welded mesh (as the CLI builds a file's part),
// with the map between the caller's vertices and the mesh's, and the geometry of the geodesics
// computed on first use.
struct Built {
  MeshBuild build;
  std::unique_ptr<SurfaceGeometry> geometry;

  const Mesh& mesh() const { return build.mesh; }
  int callerVertices() const { return static_cast<int>(build.vertexOf.size()); }
  const SurfaceGeometry& surface();
  // Per-caller-vertex rows -> per-mesh-vertex rows and back (toMeshLayout / toCallerLayout).
  std::vector<double> toMesh(const std::vector<double>& caller, int dim, bool unitVectors = false) const;
  std::vector<double> toCaller(const std::vector<double>& mesh, int dim) const;
};

// --- signals and wavelet options given per caller vertex ---------------------------------------

// The caller's per-vertex data that a signal name may refer to, copied out of Python.
struct Named {
  std::string name;
  int dim = 1;
  bool unit = false;
  std::vector<double> values;  // caller layout
};

struct Inputs {
  std::vector<double> colors;  // caller layout RGB, empty when none
  std::vector<Named> attributes;
};

// Colors ((N, 3) or (N, 4), or None) and named attributes ((N,) or (N, dim)) of the caller's N
// vertices; names in `unit` are unit vectors. InputError naming the array of another shape.
Inputs inputsOf(const Built& b, const py::handle& colors, const py::dict& attributes, const std::vector<std::string>& unit);

// The wavelet options of a call with WaveletOptions::wholeIndex, which Python gives per caller
// vertex, per mesh vertex (welded vertices take their smallest).
WaveletOptions onMesh(const Built& b, WaveletOptions w);

// --- long calls --------------------------------------------------------------------------------

class Run {
 public:
  // callback(fraction, stage) or None; it may return False to cancel.
  explicit Run(py::object callback = py::none());
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  // Calls body(progress) with the GIL released and returns its result. Raises what body throws
  // (translated by the module), KeyboardInterrupt when Ctrl-C stopped it, the callback's own
  // exception when the callback raised, geoshift.Cancelled when the callback returned False.
  template <class Body>
  auto operator()(Body&& body) -> decltype(body(std::declval<const Progress&>())) {
    using Result = decltype(body(std::declval<const Progress&>()));
    std::optional<Result> result;
    bool cancelled = false;
    {
      py::gil_scoped_release release;
      try {
        result.emplace(body(progress_));
      } catch (const Cancelled&) {
        cancelled = true;
      }
    }
    rethrowPending();
    if (cancelled || !result) throw Cancelled();
    return std::move(*result);
  }

  const Progress& progress() const { return progress_; }

 private:
  void report(double fraction, std::string_view stage);
  void rethrowPending();

  py::object callback_;
  std::atomic<bool> cancel_{false};
  Progress progress_;
  std::optional<py::error_already_set> pending_;  // set and read with the GIL held
  std::chrono::steady_clock::time_point last_{};
  std::string lastStage_;
};

}  // namespace geoshift::python

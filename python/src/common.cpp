#include "common.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace geoshift::python {

namespace {

std::string shapeOf(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

// Any numeric array (or nested list) as a C-contiguous array of T; InputError naming `what` if it
// cannot be one (strings, objects, ragged lists).
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> numeric(const py::handle& value, const std::string& what) {
  if (value.is_none()) throw InputError(what + " is missing (None)");
  try {
    py::array raw = py::array::ensure(value);
    if (!raw) throw py::error_already_set();
    const char kind = raw.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
      throw InputError(what + " must be an array of numbers (got dtype " + std::string(py::str(raw.dtype())) + ")");
    if constexpr (std::is_integral_v<T>) {
      if (kind == 'f') throw InputError(what + " must be an array of integers (got dtype " + std::string(py::str(raw.dtype())) + ")");
    }
    return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(raw);
  } catch (py::error_already_set&) {
    throw InputError(what + " must be an array of numbers");
  }
}

}  // namespace

std::vector<Vec3> toPoints(const py::handle& value, const std::string& what) {
  auto a = numeric<double>(value, what);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(what + " must have shape (N, 3) (got " + shapeOf(a) + ")");
  std::vector<Vec3> out(a.shape(0));
  const double* p = a.data();
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  return out;
}

std::vector<Face> toFaces(const py::handle& value, const std::string& what) {
  auto a = numeric<std::int64_t>(value, what);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(what + " must have shape (M, 3) (got " + shapeOf(a) + ")");
  std::vector<Face> out(a.shape(0));
  const std::int64_t* p = a.data();
  for (size_t f = 0; f < out.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = p[3 * f + k];
      if (v < 0 || v > std::numeric_limits<int>::max())
        throw InputError(what + ": face " + std::to_string(f) + " corner " + std::to_string(k) + " has index " +
                         std::to_string(v) + ", out of range");
      out[f][k] = static_cast<int>(v);
    }
  return out;
}

std::vector<double> toRows(const py::handle& value, const std::string& what, int& dim) {
  auto a = numeric<double>(value, what);
  if (a.ndim() == 1) {
    dim = 1;
  } else if (a.ndim() == 2 && a.shape(1) >= 1) {
    dim = static_cast<int>(a.shape(1));
  } else {
    throw InputError(what + " must have shape (N,) or (N, dim) (got " + shapeOf(a) + ")");
  }
  return std::vector<double>(a.data(), a.data() + a.size());
}

py::array_t<double> fromRows(const std::vector<double>& values, int dim) {
  if (dim == 1) return fromVector(values);
  py::array_t<double> out({static_cast<py::ssize_t>(values.size() / dim), static_cast<py::ssize_t>(dim)});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::array_t<double> fromPoints(const std::vector<Vec3>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  double* p = out.mutable_data();
  for (size_t i = 0; i < points.size(); ++i)
    for (int c = 0; c < 3; ++c) p[3 * i + c] = points[i][c];
  return out;
}

py::array_t<int> fromFaces(const std::vector<Face>& faces) {
  py::array_t<int> out({static_cast<py::ssize_t>(faces.size()), py::ssize_t{3}});
  int* p = out.mutable_data();
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) p[3 * f + k] = faces[f][k];
  return out;
}

const SurfaceGeometry& Built::surface() {
  if (!geometry) geometry = std::make_unique<SurfaceGeometry>(build.mesh);
  return *geometry;
}

std::vector<double> Built::toMesh(const std::vector<double>& caller, int dim, bool unitVectors) const {
  return toMeshLayout(caller, dim, build.vertexOf, build.mesh, unitVectors);
}

std::vector<double> Built::toCaller(const std::vector<double>& values, int dim) const {
  return toCallerLayout(values, dim, build.vertexOf);
}

Run::Run(py::object callback) : callback_(std::move(callback)) {
  progress_.cancel = &cancel_;
  progress_.report = [this](double fraction, std::string_view stage) { report(fraction, stage); };
}

void Run::report(double fraction, std::string_view stage) {
  // The core reports from the calling thread only (parallel.hpp). Taking the GIL is cheap alone but
  // waits for other Python threads (a Dask worker's), so at most every 50 ms and at stage changes.
  const auto now = std::chrono::steady_clock::now();
  if (stage == lastStage_ && fraction < 1 && now - last_ < std::chrono::milliseconds(50)) return;
  last_ = now;
  lastStage_ = stage;
  py::gil_scoped_acquire gil;
  if (pending_) return;
  if (PyErr_CheckSignals() != 0) {  // Ctrl-C (main thread only): stop the call, raise it afterwards
    pending_.emplace();
    cancel_ = true;
    return;
  }
  if (callback_.is_none()) return;
  try {
    py::object answer = callback_(fraction, py::str(stage.data(), stage.size()));
    if (answer.ptr() == Py_False) cancel_ = true;
  } catch (py::error_already_set& e) {
    pending_.emplace(std::move(e));
    cancel_ = true;
  }
}

void Run::rethrowPending() {
  if (!pending_) return;
  py::error_already_set e = std::move(*pending_);
  pending_.reset();
  throw e;
}

Inputs inputsOf(const Built& b, const py::handle& colors, const py::dict& attributes, const std::vector<std::string>& unit) {
  Inputs in;
  const size_t n = b.callerVertices();
  if (!colors.is_none()) {
    int dim = 0;
    std::vector<double> rows = toRows(colors, "colors", dim);
    if ((dim != 3 && dim != 4) || rows.size() != n * dim)
      throw InputError("colors must have shape (N, 3) or (N, 4) for the mesh's " + std::to_string(n) + " vertices");
    for (size_t i = 0; i < n; ++i) in.colors.insert(in.colors.end(), {rows[dim * i], rows[dim * i + 1], rows[dim * i + 2]});
  }
  for (auto [k, v] : attributes) {
    Named a;
    a.name = py::str(k);
    a.values = toRows(v, "attribute '" + a.name + "'", a.dim);
    if (a.values.size() != n * a.dim)
      throw InputError("attribute '" + a.name + "' has " + std::to_string(a.values.size() / a.dim) + " rows for the mesh's " +
                       std::to_string(n) + " vertices");
    a.unit = std::find(unit.begin(), unit.end(), a.name) != unit.end();
    in.attributes.push_back(std::move(a));
  }
  return in;
}

WaveletOptions onMesh(const Built& b, WaveletOptions w) {
  if (w.wholeIndex.empty()) return w;
  const size_t n = b.callerVertices();
  if (w.wholeIndex.size() != n)
    throw InputError("wavelet whole_index has " + std::to_string(w.wholeIndex.size()) + " entries for the mesh's " +
                     std::to_string(n) + " vertices");
  std::vector<std::int64_t> index(b.mesh().vertexCount(), std::numeric_limits<std::int64_t>::max());
  for (size_t i = 0; i < n; ++i) index[b.build.vertexOf[i]] = std::min(index[b.build.vertexOf[i]], w.wholeIndex[i]);
  w.wholeIndex = std::move(index);
  return w;
}

}  // namespace geoshift::python

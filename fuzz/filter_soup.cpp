// libFuzzer harness for one short filter run on a fuzzed mesh: the soup of fuzz/soup_bytes.hpp is
// built as the CLI builds it, then (1) a two-pass blurring mean shift of the vertex normals and
// of the height, few iterations, and (2) the default denoiser with one fixed pass, each on one
// thread so that an execution stays in the milliseconds. Clean InputErrors (bad soup, no faces
// left, ...) are expected; a result that turns finite input into NaN/Inf traps, as does anything
// the sanitizers report.
#include <cmath>
#include <cstdint>
#include <vector>

#include "geoshift/denoise.hpp"
#include "geoshift/error.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/mesh.hpp"
#include "soup_bytes.hpp"

namespace {

void requireFinite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) __builtin_trap();
}

void requireFinite(const geoshift::Mesh& mesh) {
  for (const geoshift::Vec3& p : mesh.positions())
    if (!p.allFinite()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geoshift;
  if (size > 2048) return 0;  // a few hundred faces at most: each run stays short
  geoshift::MeshBuild build;
  try {
    build = buildMesh(fuzz::soupFromBytes(data, size));
  } catch (const InputError&) {
    return 0;
  }
  try {
    FilterSignal signal = filterSignal(build.mesh, "normal", SignalInputs{});
    std::vector<double> height;
    for (const Vec3& p : build.mesh.positions()) height.push_back(p.z());
    signal.values.set("_HEIGHT", 1, AttributeKind::Euclidean, height);
    signal.channels.push_back({"_HEIGHT", 0.5, RangeKernel::Gaussian});
    MeanShiftOptions o;
    o.channels = signal.channels;
    o.passes = 2;
    o.maxIterations = 4;
    o.parallel.threads = 1;
    const MeanShiftResult r = meanShift(build.mesh, signal.values, o);
    for (const Attribute& a : r.signal.all()) requireFinite(a.values);
  } catch (const InputError&) {
  }
  try {
    Mesh mesh = build.mesh;
    DenoiseOptions d;
    d.fixedPasses = 1;
    d.presmoothing = {1};
    d.vertexIterations = 2;
    d.threads = 1;
    denoise(mesh, d);
    requireFinite(mesh);
  } catch (const InputError&) {
  }
  return 0;
}

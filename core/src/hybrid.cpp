#include "geoshift/hybrid.hpp"

#include <chrono>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift {

namespace {

// The options with their spatial quantities in hybrid.unit instead of the filtered mesh's AEL.
MeanShiftOptions inUnits(MeanShiftOptions o, const Mesh& filtered, double unit) {
  if (unit <= 0) return o;
  const double factor = unit / averageEdgeLength(filtered);
  o.spatialBandwidth *= factor;
  o.radius *= factor;  // 0 stays 0: 3 h_s, scaled with h_s
  o.epsilon *= factor;
  return o;
}

}  // namespace

HybridResult hybridMeanShift(const Mesh& mesh, const AttributeSet& signal, const MeanShiftOptions& options,
                             const HybridOptions& hybrid, const Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  HybridResult result;
  if (hybrid.levels < 0) throw InputError("hybrid filter: levels must be >= 0 (got " + std::to_string(hybrid.levels) + ")");
  if (hybrid.levels == 0) {
    result.coarse = meanShift(mesh, signal, inUnits(options, mesh, hybrid.unit), progress);
    result.signal = result.coarse.signal;
    result.positions = mesh.positions();
    result.segment = result.coarse.segment;
    result.segmentCount = result.coarse.segmentCount;
    result.vertexCounts = {mesh.vertexCount()};
    result.seconds = result.coarse.seconds;
    return result;
  }
  // Only the channels the mean shift filters go through the transform.
  AttributeSet channels(mesh.vertexCount());
  if (options.channels.empty()) {
    channels = signal;
  } else {
    for (const SignalChannel& c : options.channels) {
      const Attribute& a = signal.get(c.attribute);
      channels.set(a.name, a.dim, a.kind, a.values);
    }
  }
  WaveletOptions w = hybrid.wavelet;
  w.levels = hybrid.levels;
  const Multiresolution mr = analyze(mesh, channels, w, progress.slice(0, 0.1));
  result.vertexCounts = mr.vertexCounts();
  result.coarse = meanShift(mr.coarse, mr.coarseAttributes, inUnits(options, mr.coarse, hybrid.unit), progress.slice(0.1, 0.95));
  const SynthesisResult fine = synthesize(mr, mr.coarse.positions(), result.coarse.signal, hybrid.alpha, progress.slice(0.95, 1));
  result.signal = fine.attributes;
  result.positions = hybrid.filterGeometry ? fine.mesh.positions() : mesh.positions();
  if (options.segments) {
    // Every removed vertex joins the segment of the vertex it was collapsed into, coarse to fine.
    result.segment.assign(mesh.vertexCount(), -1);
    for (size_t c = 0; c < mr.coarseToFine.size(); ++c) result.segment[mr.coarseToFine[c]] = result.coarse.segment[c];
    for (auto level = mr.levels.rbegin(); level != mr.levels.rend(); ++level)
      for (size_t i = level->odd.size(); i-- > 0;) result.segment[level->odd[i]] = result.segment[level->target[i]];
    result.segmentCount = result.coarse.segmentCount;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geoshift

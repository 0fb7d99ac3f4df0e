#include "geoshift/hybrid.hpp"

#include <algorithm>
#include <chrono>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "hybrid_detail.hpp"

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

// filtered + gain × (lifted − restricted), per Euclidean row (hybrid_detail::edgeAwareCoarseSignal).
AttributeSet withClampResidual(const AttributeSet& filtered, const Multiresolution& mr, const AttributeSet& bounded, double gain) {
  AttributeSet out = filtered;
  for (const Attribute& lifted : mr.coarseAttributes.all()) {
    if (lifted.kind != AttributeKind::Euclidean) continue;
    std::vector<double>& values = out.find(lifted.name)->values;
    const std::vector<double>& clamped = bounded.get(lifted.name).values;
    for (size_t i = 0; i < values.size(); ++i) values[i] += gain * (lifted.values[i] - clamped[i]);
  }
  return out;
}

// The gain synthesize() gives the coarsest level's details (one value for all, or one per level).
double coarsestGain(const Multiresolution& mr, const std::vector<double>& alpha) {
  if (alpha.size() <= 1 || mr.levelCount() == 0) return alpha.empty() ? 0.0 : alpha[0];
  return alpha[std::min<size_t>(alpha.size(), mr.levelCount()) - 1];
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
  // The mean shift filters an edge-aware restriction of the signal, within its input's range
  // (hybrid_detail.hpp: the lifted one overshoots at jumps; a crease's curvature went negative).
  const AttributeSet bounded = hybrid_detail::edgeAwareCoarseSignal(mr, channels, options);
  result.coarse = meanShift(mr.coarse, bounded, inUnits(options, mr.coarse, hybrid.unit), progress.slice(0.1, 0.95));
  const bool detailsDropped = std::all_of(hybrid.alpha.begin(), hybrid.alpha.end(), [](double a) { return a == 0; });
  // With details, how the restriction differs from the lifted signal is one more detail of the
  // coarsest level, so that alpha = 1 still gives the input back when the mean shift changes nothing.
  const SynthesisResult fine = synthesize(mr, mr.coarse.positions(),
                                          detailsDropped ? result.coarse.signal : withClampResidual(result.coarse.signal, mr, bounded, coarsestGain(mr, hybrid.alpha)),
                                          hybrid.alpha, progress.slice(0.95, 1));
  // Without details the fine signal is a prediction from the coarse one: guided by the input
  // values, so that it does not average across a crease (hybrid_detail.hpp).
  result.signal = detailsDropped ? hybrid_detail::guidedProlongation(mr, result.coarse.signal, channels, options) : fine.attributes;
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

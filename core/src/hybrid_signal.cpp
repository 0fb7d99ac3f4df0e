// The hybrid filter's signal between the wavelet levels (hybrid_detail.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "hybrid_detail.hpp"

namespace geoshift::hybrid_detail {

namespace {

// h_r of an attribute as the mean shift compares it (MeanShiftOptions::channels, else the default).
double rangeBandwidthOf(const MeanShiftOptions& options, const std::string& name) {
  for (const SignalChannel& c : options.channels)
    if (c.attribute == name && c.rangeBandwidth > 0) return c.rangeBandwidth;
  return options.rangeBandwidth;
}

// Every channel's input rows side by side, divided by the channel's h_r: differences are then in
// units of h_r, as the mean shift's range kernel sees them.
std::vector<double> scaledRows(const AttributeSet& input, const MeanShiftOptions& options, int& D) {
  const int n = input.vertexCount();
  D = 0;
  for (const Attribute& a : input.all()) D += a.dim;
  std::vector<double> guide(static_cast<size_t>(n) * D);
  int c0 = 0;
  for (const Attribute& a : input.all()) {
    const double h = rangeBandwidthOf(options, a.name);
    if (!(h > 0)) throw InputError("hybrid filter: the range bandwidth of '" + a.name + "' must be positive");
    for (int v = 0; v < n; ++v)
      for (int d = 0; d < a.dim; ++d) guide[static_cast<size_t>(v) * D + c0 + d] = a.row(v)[d] / h;
    c0 += a.dim;
  }
  return guide;
}

double distance2(const std::vector<double>& guide, int D, int a, int b) {
  double s = 0;
  for (int k = 0; k < D; ++k) {
    const double x = guide[static_cast<size_t>(a) * D + k] - guide[static_cast<size_t>(b) * D + k];
    s += x * x;
  }
  return s;
}

// F's row of vertex o as the mean of the known ring vertices' rows, weighted by base times a
// Gaussian of their input distance to o (in units of h_r). False, and o untouched, when every
// weight underflows against its base (no known neighbour within ~7 h_r).
bool guidedMean(const std::vector<double>& guide, int D, int o, const std::vector<int>& ring,
                const std::vector<double>& base, const std::vector<char>& known, std::vector<double>& F,
                std::vector<double>& w) {
  double total = 0, baseTotal = 0;
  w.assign(ring.size(), 0.0);
  for (size_t q = 0; q < ring.size(); ++q) {
    if (!known[ring[q]]) continue;
    w[q] = base[q] * std::exp(-0.5 * distance2(guide, D, o, ring[q]));
    total += w[q];
    baseTotal += base[q];
  }
  if (!(total > 1e-12 * baseTotal) || !(total > 0)) return false;
  double* out = &F[static_cast<size_t>(o) * D];
  std::fill_n(out, D, 0.0);
  for (size_t q = 0; q < ring.size(); ++q) {
    if (w[q] == 0) continue;
    const double weight = w[q] / total;
    const double* from = &F[static_cast<size_t>(ring[q]) * D];
    for (int k = 0; k < D; ++k) out[k] += weight * from[k];
  }
  return true;
}

}  // namespace

AttributeSet edgeAwareCoarseSignal(const Multiresolution& mr, const AttributeSet& input, const MeanShiftOptions& options) {
  const int n = mr.fine.vertexCount();
  int D = 0;
  const std::vector<double> guide = scaledRows(input, options, D);
  // The coarse vertex each fine vertex was collapsed into, over all levels (coarse to fine).
  std::vector<int> root(n, -1);
  for (size_t c = 0; c < mr.coarseToFine.size(); ++c) root[mr.coarseToFine[c]] = mr.coarseToFine[c];
  for (auto level = mr.levels.rbegin(); level != mr.levels.rend(); ++level)
    for (size_t i = 0; i < level->odd.size(); ++i) root[level->odd[i]] = root[level->target[i]];
  const std::vector<double> area = mixedVoronoiAreas(mr.fine);
  std::vector<double> weight(n, 0.0), total(n, 0.0);
  for (int v = 0; v < n; ++v) {
    if (root[v] < 0) continue;
    // A vertex of no face has no area; it still counts for itself.
    weight[v] = std::max(area[v], 1e-300) * std::exp(-0.5 * distance2(guide, D, v, root[v]));
    total[root[v]] += weight[v];
  }
  AttributeSet out = mr.coarseAttributes;
  std::vector<int> fineToCoarse(n, -1);
  for (size_t c = 0; c < mr.coarseToFine.size(); ++c) fineToCoarse[mr.coarseToFine[c]] = static_cast<int>(c);
  for (const Attribute& a : input.all()) {
    if (a.kind != AttributeKind::Euclidean) continue;
    std::vector<double>& values = out.find(a.name)->values;
    std::fill(values.begin(), values.end(), 0.0);
    for (int v = 0; v < n; ++v) {
      if (root[v] < 0) continue;
      const double w = weight[v] / total[root[v]];
      double* dst = &values[static_cast<size_t>(fineToCoarse[root[v]]) * a.dim];
      for (int d = 0; d < a.dim; ++d) dst[d] += w * a.row(v)[d];
    }
  }
  return out;
}

AttributeSet guidedProlongation(const Multiresolution& mr, const AttributeSet& coarse, const AttributeSet& input,
                                const MeanShiftOptions& options) {
  const int n = mr.fine.vertexCount();
  const int nc = static_cast<int>(mr.coarseToFine.size());
  int D = 0;
  const std::vector<double> guide = scaledRows(input, options, D);
  std::vector<double> F(static_cast<size_t>(n) * D, 0.0);
  int c0 = 0;
  for (const Attribute& a : input.all()) {
    const Attribute* filtered = coarse.find(a.name);
    if (!filtered || filtered->dim != a.dim || filtered->vertexCount() != nc)
      throw InputError("hybrid filter: the coarse signal lacks '" + a.name + "' or has another shape");
    for (int c = 0; c < nc; ++c)
      for (int d = 0; d < a.dim; ++d) F[static_cast<size_t>(mr.coarseToFine[c]) * D + c0 + d] = filtered->row(c)[d];
    c0 += a.dim;
  }

  // Coarse vertices are known; odd ones become known as they are predicted, coarse to fine.
  std::vector<char> known(n, 0);
  for (int c : mr.coarseToFine) known[c] = 1;
  std::vector<int> deferred;
  std::vector<int> ring;
  std::vector<double> base, w;  // w: guidedMean's weights, reused
  for (auto level = mr.levels.rbegin(); level != mr.levels.rend(); ++level) {
    const WaveletLevel& L = *level;
    for (size_t i = 0; i < L.odd.size(); ++i) {
      ring.assign(L.neighbor.begin() + L.offset[i], L.neighbor.begin() + L.offset[i + 1]);
      base.assign(L.predict.begin() + L.offset[i], L.predict.begin() + L.offset[i + 1]);
      if (guidedMean(guide, D, L.odd[i], ring, base, known, F, w)) known[L.odd[i]] = 1;
      else deferred.push_back(L.odd[i]);
    }
  }
  // A vertex whose prediction ring holds no value like its own (a crease vertex the decimation
  // left among flat ones only) is read from its fine 1-ring instead, once that is known; sweeps
  // go on while they make progress.
  for (bool progress = true; progress;) {
    progress = false;
    for (int o : deferred) {
      if (known[o]) continue;
      ring = mr.fine.neighbors(o);
      base.assign(ring.size(), 1.0);
      if (guidedMean(guide, D, o, ring, base, known, F, w)) known[o] = 1, progress = true;
    }
  }
  // What is left is unlike every known neighbour (an outlier): the closest of them in the input.
  for (int o : deferred) {
    if (known[o]) continue;
    ring = mr.fine.neighbors(o);
    int closest = -1;
    double closestDistance = std::numeric_limits<double>::infinity();
    for (int q : ring) {
      const double s = distance2(guide, D, o, q);
      if (known[q] && s < closestDistance) closestDistance = s, closest = q;
    }
    if (closest >= 0) std::copy_n(&F[static_cast<size_t>(closest) * D], D, &F[static_cast<size_t>(o) * D]);
    known[o] = 1;
  }

  AttributeSet out(n);
  c0 = 0;
  for (const Attribute& a : input.all()) {
    std::vector<double> values(static_cast<size_t>(n) * a.dim);
    for (int v = 0; v < n; ++v) {
      double* dst = values.data() + static_cast<size_t>(v) * a.dim;
      std::copy_n(&F[static_cast<size_t>(v) * D + c0], a.dim, dst);
      if (a.kind == AttributeKind::UnitVector) {
        double s = 0;
        for (int d = 0; d < a.dim; ++d) s += dst[d] * dst[d];
        // As wavelet synthesis does: a row that cancelled to zero gets the first axis.
        if (s > 1e-300) {
          for (int d = 0; d < a.dim; ++d) dst[d] /= std::sqrt(s);
        } else {
          std::fill_n(dst, a.dim, 0.0);
          dst[0] = 1.0;
        }
      }
    }
    out.set(a.name, a.dim, a.kind, std::move(values));
    c0 += a.dim;
  }
  return out;
}

}  // namespace geoshift::hybrid_detail

// Lifting synthesis (docs/algorithms.md#wavelets), coarse to fine: per level undo the update with the scaled
// details, f_e -= Σ_o u_eo α d_o, then predict the odd vertices back, f_o = α d_o + Σ_e p_oe f_e.
// The odd vertices of a level are independent, so their order within the level does not matter.
#include <algorithm>
#include <cmath>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift {

namespace {

std::vector<double> gains(const Multiresolution& mr, std::span<const double> alpha) {
  const int L = mr.levelCount();
  const size_t k = alpha.size();
  if (k != 1 && k != static_cast<size_t>(L) && k != static_cast<size_t>(mr.requestedLevels))
    throw InputError("wavelet synthesis: " + std::to_string(k) + " detail gains (alpha) for " + std::to_string(L) +
                     " levels; give one value or one per level");
  for (size_t i = 0; i < k; ++i)
    if (!std::isfinite(alpha[i]))
      throw InputError("wavelet synthesis: alpha " + std::to_string(i) + " is not finite");
  std::vector<double> g(L);
  for (int l = 0; l < L; ++l) g[l] = k == 1 ? alpha[0] : alpha[l];
  return g;
}

}  // namespace

SynthesisResult synthesize(const Multiresolution& mr, const std::vector<Vec3>& coarsePositions,
                           const AttributeSet& coarseAttributes, std::span<const double> alpha,
                           const Progress& progress) {
  const std::vector<double> g = gains(mr, alpha);
  const int nc = static_cast<int>(mr.coarseToFine.size());
  if (static_cast<int>(coarsePositions.size()) != nc)
    throw InputError("wavelet synthesis: " + std::to_string(coarsePositions.size()) +
                     " coarse positions for a coarse mesh of " + std::to_string(nc) + " vertices");
  const int C = mr.channelCount();
  const int n = mr.fine.vertexCount();
  std::vector<double> G(static_cast<size_t>(n) * C, 0.0);
  auto row = [&](int v) { return G.data() + static_cast<size_t>(v) * C; };

  for (int i = 0; i < nc; ++i) {
    const Vec3& p = coarsePositions[i];
    if (!p.allFinite()) throw InputError("wavelet synthesis: coarse position " + std::to_string(i) + " is not finite");
    double* r = row(mr.coarseToFine[i]);
    r[0] = p.x(), r[1] = p.y(), r[2] = p.z();
  }
  int c0 = 3;
  for (size_t k = 1; k < mr.layout.size(); ++k) {
    const Attribute& spec = mr.layout[k];
    const Attribute* a = coarseAttributes.find(spec.name);
    if (!a) throw InputError("wavelet synthesis: the coarse attributes lack '" + spec.name + "'");
    if (a->dim != spec.dim || a->vertexCount() != nc)
      throw InputError("wavelet synthesis: coarse attribute '" + spec.name + "' has dim " + std::to_string(a->dim) +
                       " and " + std::to_string(a->vertexCount()) + " rows; expected dim " + std::to_string(spec.dim) +
                       " and " + std::to_string(nc) + " rows");
    const bool unit = spec.kind == AttributeKind::UnitVector;
    for (int i = 0; i < nc; ++i) {
      // Unit rows carry the length the lifted row had, so that unfiltered rows round-trip exactly.
      const double s = unit ? mr.coarseNorms[k][i] : 1.0;
      double* r = row(mr.coarseToFine[i]) + c0;
      const double* in = a->row(i);
      for (int d = 0; d < spec.dim; ++d) r[d] = s * in[d];
    }
    c0 += spec.dim;
  }

  std::vector<double> scaled(C);
  for (int l = mr.levelCount() - 1; l >= 0; --l) {
    progress.step(1.0 - static_cast<double>(l + 1) / mr.levelCount(), "wavelet synthesis");
    const WaveletLevel& L = mr.levels[l];
    const double a = g[l];
    const int m = static_cast<int>(L.odd.size());
    for (int i = 0; i < m; ++i) {
      const double* d = L.detail.data() + static_cast<size_t>(i) * C;
      for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) {
        double* fe = row(L.neighbor[q]);
        const double u = a * L.update[q];
        for (int c = 0; c < C; ++c) fe[c] -= u * d[c];
      }
    }
    for (int i = 0; i < m; ++i) {
      const double* d = L.detail.data() + static_cast<size_t>(i) * C;
      double* fo = row(L.odd[i]);
      for (int c = 0; c < C; ++c) fo[c] = a * d[c];
      for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) {
        const double* fe = row(L.neighbor[q]);
        const double p = L.predict[q];
        for (int c = 0; c < C; ++c) fo[c] += p * fe[c];
      }
    }
  }

  SynthesisResult out{mr.fine, AttributeSet(n)};
  for (int v = 0; v < n; ++v) {
    const double* r = row(v);
    out.mesh.position(v) = Vec3(r[0], r[1], r[2]);
  }
  c0 = 3;
  for (size_t k = 1; k < mr.layout.size(); ++k) {
    const Attribute& spec = mr.layout[k];
    std::vector<double> values(static_cast<size_t>(n) * spec.dim);
    for (int v = 0; v < n; ++v) {
      double* dst = values.data() + static_cast<size_t>(v) * spec.dim;
      std::copy_n(row(v) + c0, spec.dim, dst);
      if (spec.kind == AttributeKind::UnitVector) {
        double s = 0;
        for (int d = 0; d < spec.dim; ++d) s += dst[d] * dst[d];
        // A row that cancelled to zero (strong suppression of opposing normals) gets the first axis
        // rather than an error: the caller asked for that smoothing.
        if (!(s > 1e-300)) {
          std::fill_n(dst, spec.dim, 0.0);
          dst[0] = 1.0;
        }
      }
    }
    out.attributes.set(spec.name, spec.dim, spec.kind, std::move(values));
    c0 += spec.dim;
  }
  progress.step(1.0, "wavelet synthesis");
  return out;
}

SynthesisResult waveletFilter(const Mesh& mesh, const AttributeSet& signals, const WaveletOptions& options,
                              std::span<const double> alpha, const Progress& progress) {
  if (alpha.size() != 1 && alpha.size() != static_cast<size_t>(std::max(options.levels, 0)))
    throw InputError("wavelet filter: " + std::to_string(alpha.size()) + " detail gains (alpha) for " +
                     std::to_string(options.levels) + " levels; give one value or one per level");
  const Multiresolution mr = analyze(mesh, signals, options, progress);
  return synthesize(mr, mr.coarse.positions(), mr.coarseAttributes, alpha, progress);
}

}  // namespace geoshift

// Prediction weights and candidate ordering of the wavelet analysis (wavelet_detail.hpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "wavelet_detail.hpp"

namespace geoshift::wavelet_detail {

// Prediction weights over the ring (interior) or the two boundary neighbours (boundary), summing to 1.
void predictionWeights(int o, const Ring& r, const PositionRows& x, WaveletWeights kind,
                       std::vector<int>& nbr, std::vector<double>& w) {
  nbr.clear();
  w.clear();
  const Vec3 xo = x(o);
  if (r.boundary) {
    const int a = r.vertex.back(), b = r.vertex.front();
    const double da = (x(a) - xo).norm(), db = (x(b) - xo).norm();
    nbr = {a, b};
    // Linear interpolation along the polyline (what inverse distance and mean value give in 1D).
    if (kind == WaveletWeights::Uniform || !(da + db > 0)) w = {0.5, 0.5};
    else w = {db / (da + db), da / (da + db)};
    return;
  }
  const int n = static_cast<int>(r.vertex.size());
  nbr = r.vertex;
  w.assign(n, 1.0);
  if (kind == WaveletWeights::InverseDistance) {
    for (int i = 0; i < n; ++i) w[i] = 1.0 / (x(nbr[i]) - xo).norm();
  } else if (kind == WaveletWeights::MeanValue) {
    // w_i = (tan(α_{i-1}/2) + tan(α_i/2)) / r_i, α_i the angle at o between n_i and n_{i+1},
    // tan(α/2) = |a×b| / (|a||b| + a·b).
    thread_local std::vector<double> tanHalf;
    tanHalf.resize(n);
    for (int i = 0; i < n; ++i) {
      const Vec3 a = x(nbr[i]) - xo, b = x(nbr[(i + 1) % n]) - xo;
      tanHalf[i] = a.cross(b).norm() / (a.norm() * b.norm() + a.dot(b));
    }
    for (int i = 0; i < n; ++i) w[i] = (tanHalf[(i + n - 1) % n] + tanHalf[i]) / (x(nbr[i]) - xo).norm();
  }
  double sum = 0;
  for (double v : w) sum += v;
  if (!std::isfinite(sum) || !(sum > 0)) {
    w.assign(n, 1.0);
    sum = n;
  }
  for (double& v : w) v /= sum;
}

double turnCosine(int v, const Ring& r, const PositionRows& x) {
  const Vec3 in = x(v) - x(r.vertex.back()), out = x(r.vertex.front()) - x(v);
  const double d = in.norm() * out.norm();
  return d > 0 ? in.dot(out) / d : -1.0;
}

// Ascending cost in kCostBands quantile bands, each band in vertex order. A strict sort would visit
// the mesh in random order (ties and noise in the cost), which on large meshes makes every step a
// cache miss; bands keep the cost ordering where it matters (cheap first) at streaming speed. The
// bands are taken block by block of kOrderBlock vertex indices: one sweep of a band over a
// million-vertex mesh leaves the cache before the next band comes back, while a block's one-rings
// stay in L2 (about 1.4x faster analysis on a 1M terrain). Only vertices near a block seam see
// another order. Blocks are index ranges, not runs of candidates, and the bounds can be given, so
// that the place of a vertex depends on nothing but its own cost and index (docs/tiles.md).

std::vector<double> costBandBounds(const std::vector<double>& cost) {
  const size_t n = cost.size();
  std::vector<double> sample;
  const size_t step = std::max<size_t>(1, n / 4096);
  for (size_t i = 0; i < n; i += step) sample.push_back(cost[i]);
  std::sort(sample.begin(), sample.end());
  std::vector<double> bounds;
  for (int b = 1; b < kCostBands && !sample.empty(); ++b) bounds.push_back(sample[sample.size() * b / kCostBands]);
  return bounds;
}

std::vector<int> bandedOrder(const std::vector<int>& vertices, const std::vector<double>& cost,
                             const std::vector<double>& bounds, const std::int64_t* wholeIndex) {
  const size_t n = vertices.size();
  std::vector<unsigned char> band(n);
  // The count of bounds not above the cost is upper_bound's index, without its unpredictable branches.
  const int nb = static_cast<int>(bounds.size());
  for (size_t i = 0; i < n; ++i) {
    int b = 0;
    for (int k = 0; k < nb; ++k) b += !(cost[i] < bounds[k]);
    band[i] = static_cast<unsigned char>(b);
  }
  const auto block = [&](size_t i) { return (wholeIndex ? wholeIndex[vertices[i]] : vertices[i]) / kOrderBlock; };
  std::vector<int> order(n);
  for (size_t b0 = 0, b1; b0 < n; b0 = b1) {
    for (b1 = b0 + 1; b1 < n && block(b1) == block(b0);) ++b1;
    std::array<size_t, kCostBands + 1> start{};
    for (size_t i = b0; i < b1; ++i) ++start[band[i] + 1];
    start[0] = b0;
    for (int b = 0; b < kCostBands; ++b) start[b + 1] += start[b];
    for (size_t i = b0; i < b1; ++i) order[start[band[i]]++] = vertices[i];
  }
  return order;
}

}  // namespace geoshift::wavelet_detail

// The kernel loop of one mean shift iteration for the common channel sets, written so that the
// compiler vectorises it: the chart's entries and their signal in flat arrays read in sequence,
// no branch per entry (excluded entries get weight 0), an exponential without a branch or a libm
// call, and the sums in four interleaved lanes. Most of a filter's time is spent here.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

namespace {

constexpr double kMaxExponent = 700;  // as in the general loop: beyond, a weight no sum notices
constexpr int kBlock = 32;            // entries per block of weights

// e^−a for a in [0, 700]: x = −a = n ln2 + t with |t| ≤ ln2/2, a degree-11 Taylor polynomial of e^t
// (truncation below 1.3e-14 relative) and 2^n assembled in the exponent bits of the rounding shift
// (the low bits of 1.5·2^52 + n hold n; (bits + 1023) << 52 keeps only n + 1023 in the exponent).
[[gnu::always_inline]] inline double expNegative(double a) {
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00, kShift = 6755399441055744.0;
  const double x = -a;
  const double shifted = x * kInvLn2 + kShift;
  const double n = shifted - kShift;
  const double t = (x - n * kLn2Hi) - n * kLn2Lo;
  double p = 1.0 / 39916800;
  p = p * t + 1.0 / 3628800;
  p = p * t + 1.0 / 362880;
  p = p * t + 1.0 / 40320;
  p = p * t + 1.0 / 5040;
  p = p * t + 1.0 / 720;
  p = p * t + 1.0 / 120;
  p = p * t + 1.0 / 24;
  p = p * t + 1.0 / 6;
  p = p * t + 0.5;
  p = p * t + 1.0;
  p = p * t + 1.0;
  std::uint64_t bits;
  std::memcpy(&bits, &shifted, sizeof bits);
  bits = (bits + 1023) << 52;
  double scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

// −log of the Gaussian range kernel (eq. 9) of W dimensions; coef = 1/2h_r² per dimension.
template <int W>
struct GaussianRange {
  double y[W], coef[W];
  [[gnu::always_inline]] double operator()(const double* v, size_t stride) const {
    double a = 0;
    for (int d = 0; d < W; ++d) {
      const double t = y[d] - v[d * stride];
      a += t * t * coef[d];
    }
    return a;
  }
};

// The normal-similarity kernel (eq. 8) normalised at equal normals, as in the general loop; normals
// more than ~176° apart (similarity ≤ 1e-3) are excluded.
struct SimilarityRange {
  double y[3], coef;
  [[gnu::always_inline]] double operator()(const double* v, size_t stride) const {
    const double sim = 0.5 + 0.5 * (y[0] * v[0] + y[1] * v[stride] + y[2] * v[2 * stride]);
    const double s = std::max(sim, 1e-3);
    return sim > 1e-3 ? (1 / (s * s) - 1) * coef : 2 * kMaxExponent;
  }
};

// Adds the entries [begin, end) to the lanes; W joint Euclidean dimensions accumulate when `joint`.
template <int W, class Range>
void addRun(const Chart& chart, const Climber::Samples& samples, int begin, int end, double qx, double qy,
            double invTwoHs2, double r2, const Range& range, bool joint, Climber::Lanes& lanes) {
  const double* x = chart.x.data();
  const double* y = chart.y.data();
  const double* weight = samples.weight.data();
  const double* value = samples.value.data();
  const size_t stride = samples.stride;
  double w[kBlock], dx[kBlock], dy[kBlock];
  double sw[4], mx[4], my[4], acc[W > 0 ? W : 1][4];
  std::copy(lanes.sw, lanes.sw + 4, sw);
  std::copy(lanes.mx, lanes.mx + 4, mx);
  std::copy(lanes.my, lanes.my + 4, my);
  for (int d = 0; d < W; ++d) std::copy(lanes.acc[d], lanes.acc[d] + 4, acc[d]);
  for (int start = begin; start < end; start += kBlock) {
    const int m = std::min(kBlock, end - start);
    for (int i = 0; i < m; ++i) {
      const int e = start + i;
      const double ex = x[e] - qx, ey = y[e] - qy, d2 = ex * ex + ey * ey;
      const double a = d2 * invTwoHs2 + range(value + e, stride);
      const double k = weight[e] * expNegative(std::min(a, kMaxExponent));
      const bool keep = (d2 <= r2) & (a < kMaxExponent);
      w[i] = keep ? k : 0.0;
      dx[i] = ex;
      dy[i] = ey;
    }
    const int m4 = (m + 3) & ~3;  // whole groups of four lanes: the tail adds zeros
    for (int i = m; i < m4; ++i) w[i] = dx[i] = dy[i] = 0;
    for (int i = 0; i < m4; i += 4)
      for (int l = 0; l < 4; ++l) {
        sw[l] += w[i + l];
        mx[l] += w[i + l] * dx[i + l];
        my[l] += w[i + l] * dy[i + l];
      }
    if (!joint) continue;
    for (int d = 0; d < W; ++d) {
      const double* v = value + d * stride + start;
      double tail[4] = {};
      for (int i = 0; i < m4; i += 4)
        for (int l = 0; l < 4; ++l) acc[d][l] += w[i + l] * (i + l < m ? v[i + l] : tail[l]);
    }
  }
  std::copy(sw, sw + 4, lanes.sw);
  std::copy(mx, mx + 4, lanes.mx);
  std::copy(my, my + 4, lanes.my);
  for (int d = 0; d < W; ++d) std::copy(acc[d], acc[d] + 4, lanes.acc[d]);
}

template <int W, class Range>
void addChart(const Chart& chart, const Climber::Samples& samples, double qx, double qy, const Setup& s,
              const Range& range, Climber::Lanes& lanes) {
  forEachRun(chart, qx, qy, s.r, [&](int begin, int end) {
    addRun<W>(chart, samples, begin, end, qx, qy, s.invTwoHs2, s.r2, range, s.joint, lanes);
  });
}

template <int W>
void addGaussian(const Chart& chart, const Climber::Samples& samples, double qx, double qy, const Setup& s,
                 const double* value, Climber::Lanes& lanes) {
  GaussianRange<W> range;
  for (int d = 0; d < W; ++d) {
    range.y[d] = value[d];
    range.coef[d] = s.coef[d];
  }
  addChart<W>(chart, samples, qx, qy, s, range, lanes);
}

}  // namespace

void Climber::gather(Samples& samples, const Chart& chart, const std::vector<double>& signal) const {
  const size_t n = chart.vertex.size();
  const int width = s_.width;
  samples.stride = n;
  samples.weight.resize(n);
  samples.value.resize(n * width);
  for (size_t e = 0; e < n; ++e) {
    const int v = chart.vertex[e];
    samples.weight[e] = s_.sampleWeight[v];
    const double* row = &signal[static_cast<size_t>(v) * width];
    for (int d = 0; d < width; ++d) samples.value[d * n + e] = row[d];
  }
}

namespace {

// The loop for the setup's channel set; false when there is no specialised one.
[[gnu::always_inline]] inline bool sums(const Setup& s, const Chart& chart, const Climber::Samples& samples, double qx,
                                        double qy, const double* y, Climber::Lanes& lanes) {
  switch (s.loop) {
    case Setup::Loop::Gaussian:
      switch (s.width) {
        case 1: addGaussian<1>(chart, samples, qx, qy, s, y, lanes); return true;
        case 2: addGaussian<2>(chart, samples, qx, qy, s, y, lanes); return true;
        case 3: addGaussian<3>(chart, samples, qx, qy, s, y, lanes); return true;
        case 4: addGaussian<4>(chart, samples, qx, qy, s, y, lanes); return true;
        default: return false;
      }
    case Setup::Loop::Similarity: {
      const SimilarityRange range{{y[0], y[1], y[2]}, s.channels.front().invTwoHr2};
      addChart<0>(chart, samples, qx, qy, s, range, lanes);
      return true;
    }
    default: return false;
  }
}

// The same loop compiled for the baseline instruction set and, on x86-64, for AVX2 (four doubles a
// vector instead of two), chosen at run time. Both do the same IEEE operations on every entry and
// add in the same lanes (AVX2 alone brings no fused multiply-add), so their results are identical.
[[gnu::flatten]] bool sumsBaseline(const Setup& s, const Chart& chart, const Climber::Samples& samples, double qx,
                                   double qy, const double* y, Climber::Lanes& lanes) {
  return sums(s, chart, samples, qx, qy, y, lanes);
}

#if defined(__x86_64__) && defined(__GNUC__)
[[gnu::flatten, gnu::target("avx2")]] bool sumsAvx2(const Setup& s, const Chart& chart,
                                                     const Climber::Samples& samples, double qx, double qy,
                                                     const double* y, Climber::Lanes& lanes) {
  return sums(s, chart, samples, qx, qy, y, lanes);
}
#endif

}  // namespace

bool Climber::kernelSums(const Chart& chart, const Samples& samples, double qx, double qy, Lanes& lanes) const {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool avx2 = [] {
    __builtin_cpu_init();  // a static initialiser may run before the library's own
    return __builtin_cpu_supports("avx2") != 0;
  }();
  if (avx2) return sumsAvx2(s_, chart, samples, qx, qy, value_.data(), lanes);
#endif
  return sumsBaseline(s_, chart, samples, qx, qy, value_.data(), lanes);
}

}  // namespace geoshift::mean_shift_detail

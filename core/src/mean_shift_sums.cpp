// The kernel loop of one mean shift iteration for the common channel sets, in vectors of four
// entries (GCC/Clang vector extensions: AVX2 registers where the CPU has them, two SSE2 halves
// otherwise, scalar code in plain wasm): the chart's entries and their signal in flat arrays read in
// sequence, no branch per entry (excluded entries get weight 0), an exponential without a branch
// or a libm call. Lane l of the sums holds the entries at offsets ≡ l (mod 4) from each run's start,
// on every target, so the results do not depend on the instruction set. Most of a filter's time is
// spent here.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

namespace {

using V = double __attribute__((vector_size(32)));
using Bits = std::int64_t __attribute__((vector_size(32)));

constexpr double kMaxExponent = 700;  // as in the general loop: beyond, a weight no sum notices

[[gnu::always_inline]] inline V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

[[gnu::always_inline]] inline V select(Bits mask, V a) { return reinterpret_cast<V>(reinterpret_cast<Bits>(a) & mask); }

// e^−a for a in [0, 700]: x = −a = n ln2 + t with |t| ≤ ln2/2, a degree-11 Taylor polynomial of e^t
// (truncation below 1.3e-14 relative) and 2^n assembled in the exponent bits of the rounding shift
// (the low bits of 1.5·2^52 + n hold n; (bits + 1023) << 52 keeps only n + 1023 in the exponent).
[[gnu::always_inline]] inline V expNegative(V a) {
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00, kShift = 6755399441055744.0;
  const V x = -a;
  const V shifted = x * kInvLn2 + kShift;
  const V n = shifted - kShift;
  const V t = (x - n * kLn2Hi) - n * kLn2Lo;
  // Estrin's scheme: a dependency chain of depth 7 instead of Horner's 22, so that consecutive
  // vectors overlap in the pipeline.
  const V t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
  const V q0 = 1.0 + t, q1 = 0.5 + t * (1.0 / 6), q2 = 1.0 / 24 + t * (1.0 / 120), q3 = 1.0 / 720 + t * (1.0 / 5040),
          q4 = 1.0 / 40320 + t * (1.0 / 362880), q5 = 1.0 / 3628800 + t * (1.0 / 39916800);
  const V p = (q0 + t2 * q1) + t4 * (q2 + t2 * q3) + t8 * (q4 + t2 * q5);
  const Bits scale = (reinterpret_cast<Bits>(shifted) + 1023) << 52;
  return p * reinterpret_cast<V>(scale);
}

// −log of the Gaussian range kernel (eq. 9) of W dimensions; coef = 1/2h_r² per dimension.
template <int W>
struct GaussianRange {
  static constexpr int kDims = W;  // signal dimensions read
  double y[W], coef[W];
  // Exponent and a mask of the entries the kernel keeps (all of them).
  [[gnu::always_inline]] V operator()(const double* v, size_t stride, Bits& keep) const {
    V a = V{} + 0.0;
    for (int d = 0; d < W; ++d) {
      const V t = y[d] - load(v + d * stride);
      a += t * t * coef[d];
    }
    keep = Bits{} - 1;
    return a;
  }
};

// The normal-similarity kernel (eq. 8) normalised at equal normals, as in the general loop; normals
// more than ~176° apart (similarity ≤ 1e-3) are excluded.
struct SimilarityRange {
  static constexpr int kDims = 3;
  double y[3], coef;
  [[gnu::always_inline]] V operator()(const double* v, size_t stride, Bits& keep) const {
    const V sim = 0.5 + 0.5 * (y[0] * load(v) + y[1] * load(v + stride) + y[2] * load(v + 2 * stride));
    keep = sim > 1e-3;
    const V s = sim > 1e-3 ? sim : V{} + 1.0;
    return (1 / (s * s) - 1) * coef;
  }
};

struct Sums {
  V sw = V{}, mx = V{}, my = V{};
  V acc[4] = {V{}, V{}, V{}, V{}};  // joint Euclidean updates of up to 4 dimensions
};

// An iteration's sums, the four lanes added in one fixed order.
struct Totals {
  double sw = 0, mx = 0, my = 0, acc[4] = {};
};

inline double total(V lanes) { return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]); }

// Adds four entries starting at e (read from the arrays given) to the sums.
template <int W, class Range>
[[gnu::always_inline]] inline void addFour(const double* x, const double* y, const double* weight, const double* value,
                                           size_t stride, V qx, V qy, double invTwoHs2, double r2, const Range& range,
                                           bool joint, Sums& sums) {
  const V dx = load(x) - qx, dy = load(y) - qy, d2 = dx * dx + dy * dy;
  Bits keep;
  const V a = d2 * invTwoHs2 + range(value, stride, keep);
  const V k = load(weight) * expNegative(a < kMaxExponent ? a : V{} + kMaxExponent);
  const V w = select(keep & (d2 <= r2) & (a < kMaxExponent), k);
  sums.sw += w;
  sums.mx += w * dx;
  sums.my += w * dy;
  if (joint)
    for (int d = 0; d < W; ++d) sums.acc[d] += w * load(value + d * stride);
}

// Adds the entries [begin, end); W joint Euclidean dimensions accumulate when `joint`.
template <int W, class Range>
[[gnu::always_inline]] inline void addRun(const Chart& chart, const Climber::Samples& samples, int begin, int end,
                                          double qx, double qy, double invTwoHs2, double r2, const Range& range,
                                          bool joint, Sums& sums) {
  const double* value = samples.value.data();
  const size_t stride = samples.stride;
  const V vx = V{} + qx, vy = V{} + qy;
  int e = begin;
  for (; e + 4 <= end; e += 4)
    addFour<W>(chart.x.data() + e, chart.y.data() + e, samples.weight.data() + e, value + e, stride, vx, vy, invTwoHs2,
               r2, range, joint, sums);
  if (e == end) return;
  // The last one to three entries, padded with weight-0 entries at the iterate's own place and value.
  const int m = end - e;
  double x[4], y[4], weight[4], padded[4 * Range::kDims];
  for (int i = 0; i < 4; ++i) {
    x[i] = i < m ? chart.x[e + i] : qx;
    y[i] = i < m ? chart.y[e + i] : qy;
    weight[i] = i < m ? samples.weight[e + i] : 0.0;
    for (int d = 0; d < Range::kDims; ++d) padded[d * 4 + i] = i < m ? value[d * stride + e + i] : range.y[d];
  }
  addFour<W>(x, y, weight, padded, 4, vx, vy, invTwoHs2, r2, range, joint, sums);
}

template <int W, class Range>
[[gnu::always_inline]] inline void addChart(const Chart& chart, const Climber::Samples& samples, double qx, double qy,
                                            const Setup& s, const Range& range, Totals& totals) {
  Sums sums;
  forEachRun(chart, qx, qy, s.r, [&](int begin, int end) {
    addRun<W>(chart, samples, begin, end, qx, qy, s.invTwoHs2, s.r2, range, s.joint, sums);
  });
  totals.sw = total(sums.sw);
  totals.mx = total(sums.mx);
  totals.my = total(sums.my);
  for (int d = 0; d < W; ++d) totals.acc[d] = total(sums.acc[d]);
}

template <int W>
void addGaussian(const Chart& chart, const Climber::Samples& samples, double qx, double qy, const Setup& s,
                 const double* value, Totals& totals) {
  GaussianRange<W> range;
  for (int d = 0; d < W; ++d) {
    range.y[d] = value[d];
    range.coef[d] = s.coef[d];
  }
  addChart<W>(chart, samples, qx, qy, s, range, totals);
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

// The loop for the setup's channel set (makeSetup chooses Gaussian only for up to 4 dimensions).
[[gnu::always_inline]] inline void sums(const Setup& s, const Chart& chart, const Climber::Samples& samples, double qx,
                                        double qy, const double* y, Totals& totals) {
  switch (s.loop) {
    case Setup::Loop::Gaussian:
      switch (s.width) {
        case 1: addGaussian<1>(chart, samples, qx, qy, s, y, totals); break;
        case 2: addGaussian<2>(chart, samples, qx, qy, s, y, totals); break;
        case 3: addGaussian<3>(chart, samples, qx, qy, s, y, totals); break;
        default: addGaussian<4>(chart, samples, qx, qy, s, y, totals); break;
      }
      break;
    case Setup::Loop::Similarity:
      addChart<0>(chart, samples, qx, qy, s, SimilarityRange{{y[0], y[1], y[2]}, s.channels.front().invTwoHr2}, totals);
      break;
    case Setup::Loop::General: break;  // never called: Climber::generalSums
  }
}

// The same loop compiled for the baseline instruction set and, on x86-64, for AVX2 (four doubles a
// vector instead of two), chosen at run time. Both do the same IEEE operations on every entry and
// add in the same lanes (AVX2 alone brings no fused multiply-add), so their results are identical.
[[gnu::flatten]] void sumsBaseline(const Setup& s, const Chart& chart, const Climber::Samples& samples, double qx,
                                   double qy, const double* y, Totals& totals) {
  sums(s, chart, samples, qx, qy, y, totals);
}

#if defined(__x86_64__) && defined(__GNUC__)
[[gnu::flatten, gnu::target("avx2")]] void sumsAvx2(const Setup& s, const Chart& chart,
                                                     const Climber::Samples& samples, double qx, double qy,
                                                     const double* y, Totals& totals) {
  sums(s, chart, samples, qx, qy, y, totals);
}
#endif

}  // namespace

void Climber::kernelSums(const Chart& chart, const Samples& samples, double qx, double qy, double& sw, double& mx,
                         double& my) {
  Totals totals;
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool avx2 = [] {
    __builtin_cpu_init();  // a static initialiser may run before the library's own
    return __builtin_cpu_supports("avx2") != 0;
  }();
  if (avx2)
    sumsAvx2(s_, chart, samples, qx, qy, value_.data(), totals);
  else
#endif
    sumsBaseline(s_, chart, samples, qx, qy, value_.data(), totals);
  sw = totals.sw;
  mx = totals.mx;
  my = totals.my;
  if (s_.joint)
    for (int d = 0; d < s_.width; ++d) acc_[d] = totals.acc[d];
}

}  // namespace geoshift::mean_shift_detail

// The kernel loop of one mean shift iteration for the common channel sets, in 32-byte vectors (GCC/
// Clang vector extensions: AVX2 registers where the CPU has them, two SSE2 halves otherwise, scalar
// code in plain wasm): the chart's entries and their signal in flat arrays read in sequence, no
// branch per entry (excluded entries get weight 0), an exponential without a branch or a libm call.
// Weights are computed in single precision (eight entries a vector) unless the options ask for
// double (four); single-precision sums are moved into double lanes after every run of cells.
// Lane l of the sums holds the entries at offsets ≡ l (mod lanes) from each run's start, on every
// target, so the results do not depend on the instruction set. Most of a filter's time is spent here.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "mean_shift_climb.hpp"

namespace geoshift::mean_shift_detail {

namespace {

constexpr double kLog2e = 1.44269504088896340736;  // single-precision exponents are in base 2

// The double lanes that sums end in, and half a single-precision vector on its way there.
using Double4 = double __attribute__((vector_size(32)));
using Float4 = float __attribute__((vector_size(16)));

template <class T>
struct Lanes;
template <>
struct Lanes<double> {
  using Vec = double __attribute__((vector_size(32)));
  using Bits = std::int64_t __attribute__((vector_size(32)));
  static constexpr int N = 4;
  static constexpr double kMaxExponent = mean_shift_detail::kMaxExponent;  // as in the general loop
  static constexpr double kMaxExponent2 = kMaxExponent;  // (base-2 exponents are single precision only)
};
template <>
struct Lanes<float> {
  using Vec = float __attribute__((vector_size(32)));
  using Bits = std::int32_t __attribute__((vector_size(32)));
  static constexpr int N = 8;
  // e^−70 ≈ 4e-31 keeps weights (normalised to a mean sample weight of 1) and their products with
  // coordinates (about units of h_s) clear of subnormals, which cost a microcode assist each; in
  // base 2 (Gaussian range kernels), 2^−100 ≈ 8e-31.
  static constexpr float kMaxExponent = 70, kMaxExponent2 = 100;
};

template <class T>
[[gnu::always_inline]] inline typename Lanes<T>::Vec load(const T* p) {
  typename Lanes<T>::Vec v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <class T>
[[gnu::always_inline]] inline typename Lanes<T>::Vec select(typename Lanes<T>::Bits mask, typename Lanes<T>::Vec a) {
  using Bits = typename Lanes<T>::Bits;
  return reinterpret_cast<typename Lanes<T>::Vec>(reinterpret_cast<Bits>(a) & mask);
}

// e^−a for a in [0, kMaxExponent]: x = −a = n ln2 + t with |t| ≤ ln2/2, a Taylor polynomial of e^t
// and 2^n assembled in the exponent bits of the rounding shift (the low bits of 1.5·2^52, or
// 1.5·2^23, hold n; (bits + bias) << mantissa bits keeps only n + bias in the exponent).
// Double: degree 11 (truncation below 1.3e-14 relative). Float: degree 7 (below 6e-9, under the
// format's own rounding).
[[gnu::always_inline]] inline Lanes<double>::Vec expNegative(Lanes<double>::Vec a) {
  using Vec = Lanes<double>::Vec;
  using Bits = Lanes<double>::Bits;
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00, kShift = 6755399441055744.0;
  const Vec x = -a;
  const Vec shifted = x * kInvLn2 + kShift;
  const Vec n = shifted - kShift;
  const Vec t = (x - n * kLn2Hi) - n * kLn2Lo;
  // Estrin's scheme: a dependency chain of depth 7 instead of Horner's 22, so that consecutive
  // vectors overlap in the pipeline.
  const Vec t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
  const Vec q0 = 1.0 + t, q1 = 0.5 + t * (1.0 / 6), q2 = 1.0 / 24 + t * (1.0 / 120), q3 = 1.0 / 720 + t * (1.0 / 5040),
            q4 = 1.0 / 40320 + t * (1.0 / 362880), q5 = 1.0 / 3628800 + t * (1.0 / 39916800);
  const Vec p = (q0 + t2 * q1) + t4 * (q2 + t2 * q3) + t8 * (q4 + t2 * q5);
  const Bits scale = (reinterpret_cast<Bits>(shifted) + 1023) << 52;
  return p * reinterpret_cast<Vec>(scale);
}

[[gnu::always_inline]] inline Lanes<float>::Vec expNegative(Lanes<float>::Vec a) {
  using Vec = Lanes<float>::Vec;
  using Bits = Lanes<float>::Bits;
  // ln 2 split so that n·kLn2Hi is exact for |n| < 2^11 (kLn2Hi has 12 significant bits).
  constexpr float kLn2Hi = 0.693359375f, kLn2Lo = -2.12194440e-4f;
  constexpr float kInvLn2 = 1.44269504f, kShift = 12582912.0f;
  const Vec x = -a;
  const Vec shifted = x * kInvLn2 + kShift;
  const Vec n = shifted - kShift;
  const Vec t = (x - n * kLn2Hi) - n * kLn2Lo;
  const Vec t2 = t * t, t4 = t2 * t2;
  const Vec q0 = 1.0f + t, q1 = 0.5f + t * (1.0f / 6), q2 = 1.0f / 24 + t * (1.0f / 120),
            q3 = 1.0f / 720 + t * (1.0f / 5040);
  const Vec p = (q0 + t2 * q1) + t4 * (q2 + t2 * q3);
  const Bits scale = (reinterpret_cast<Bits>(shifted) + 127) << 23;
  return p * reinterpret_cast<Vec>(scale);
}

// 2^−a for a in [0, kMaxExponent2], single precision (Gaussian range kernels, whose exponents the
// scaled samples give in base 2: Samples). No reduction by ln 2: n = round(−a), t = −a − n
// in [−1/2, 1/2] exactly, 2^t = e^(t ln 2) by its degree-7 Taylor polynomial (truncation below 6e-9
// relative, under the format's own rounding). The loop runs 1.2× faster than with e^−a.
[[gnu::always_inline]] inline Lanes<float>::Vec exp2Negative(Lanes<float>::Vec a) {
  using Vec = Lanes<float>::Vec;
  using Bits = Lanes<float>::Bits;
  constexpr float kShift = 12582912.0f;
  constexpr float c1 = 0.693147181f, c2 = 0.240226507f, c3 = 0.0555041087f, c4 = 0.00961812911f,
                  c5 = 0.00133335581f, c6 = 0.000154035304f, c7 = 1.52527338e-05f;
  const Vec shifted = kShift - a;
  const Vec n = shifted - kShift;
  const Vec t = (Vec{} - a) - n;
  const Vec t2 = t * t, t4 = t2 * t2;
  const Vec p = (1.0f + t * c1 + t2 * (c2 + t * c3)) + t4 * ((c4 + t * c5) + t2 * (c6 + t * c7));
  const Bits scale = (reinterpret_cast<Bits>(shifted) + 127) << 23;
  return p * reinterpret_cast<Vec>(scale);
}

// −log of the Gaussian range kernel (eq. 9) of W dimensions; coef = 1/2h_r² per dimension (double).
// Single precision: −log2, from values scaled by √(coef · log2 e) (ChartProvider::gather), no coef.
template <class T, int W>
struct GaussianRange {
  using Vec = typename Lanes<T>::Vec;
  using Bits = typename Lanes<T>::Bits;
  static constexpr int kDims = W;  // signal dimensions read
  static constexpr bool kBase2 = std::is_same_v<T, float>;  // exponents in base 2 (addLanes)
  T y[W], coef[W];
  // Exponent and a mask of the entries the kernel keeps (all of them).
  [[gnu::always_inline]] Vec operator()(const T* v, size_t stride, Bits& keep) const {
    Vec a = Vec{} + T(0);
    for (int d = 0; d < W; ++d) {
      const Vec t = y[d] - load(v + d * stride);
      if constexpr (std::is_same_v<T, float>)
        a += t * t;
      else
        a += t * t * coef[d];
    }
    keep = Bits{} - 1;
    return a;
  }
};

// The normal-similarity kernel (eq. 8) normalised at equal normals, as in the general loop; normals
// more than ~176° apart (similarity ≤ 1e-3) are excluded. coef = 1/2h_r².
template <class T>
struct SimilarityRange {
  using Vec = typename Lanes<T>::Vec;
  using Bits = typename Lanes<T>::Bits;
  static constexpr int kDims = 3;
  // Natural exponents: in base 2 a few normals at flat modes moved 4× farther from their
  // double-precision values (test_mean_shift), for no gain worth it.
  static constexpr bool kBase2 = false;
  T y[3], coef;
  [[gnu::always_inline]] Vec operator()(const T* v, size_t stride, Bits& keep) const {
    const Vec sim = T(0.5) + T(0.5) * (y[0] * load(v) + y[1] * load(v + stride) + y[2] * load(v + 2 * stride));
    keep = sim > T(1e-3);
    const Vec s = sim > T(1e-3) ? sim : Vec{} + T(1);
    return (T(1) / (s * s) - T(1)) * coef;
  }
};

// Double lanes: 4 for double sums, 8 (two vectors) for single-precision runs moved into them.
template <class T>
struct Sums {
  using Vec = typename Lanes<T>::Vec;
  static constexpr int kHalves = Lanes<T>::N / 4;
  Vec sw = Vec{}, mx = Vec{}, my = Vec{};
  Vec acc[4] = {Vec{}, Vec{}, Vec{}, Vec{}};  // joint Euclidean updates of up to 4 dimensions
  Double4 dsw[kHalves] = {}, dmx[kHalves] = {}, dmy[kHalves] = {}, dacc[4][kHalves] = {};
};

// After a run: single-precision lanes into their double lanes (and restart); nothing for double.
template <int W>
[[gnu::always_inline]] inline void flushRun(Sums<double>&, bool) {}

[[gnu::always_inline]] inline void widen(Lanes<float>::Vec& from, Double4* to) {
  const Float4 lo = __builtin_shufflevector(from, from, 0, 1, 2, 3), hi = __builtin_shufflevector(from, from, 4, 5, 6, 7);
  to[0] += __builtin_convertvector(lo, Double4);
  to[1] += __builtin_convertvector(hi, Double4);
  from = Lanes<float>::Vec{};
}

template <int W>
[[gnu::always_inline]] inline void flushRun(Sums<float>& sums, bool joint) {
  widen(sums.sw, sums.dsw);
  widen(sums.mx, sums.dmx);
  widen(sums.my, sums.dmy);
  if (joint)
    for (int d = 0; d < W; ++d) widen(sums.acc[d], sums.dacc[d]);
}

// The double lanes of a sum added in one fixed order.
template <class T>
inline double total(typename Lanes<T>::Vec lanes, const Double4* wide) {
  if constexpr (Lanes<T>::N == 4) {
    return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
  } else {
    const Double4& a = wide[0];
    const Double4& b = wide[1];
    return ((a[0] + a[1]) + (a[2] + a[3])) + ((b[0] + b[1]) + (b[2] + b[3]));
  }
}

// An iteration's sums, the lanes added in one fixed order.
struct Totals {
  double sw = 0, mx = 0, my = 0, acc[4] = {};
};

// What an iteration's loop reads, in the precision of its weights: for single precision, chart
// coordinates in units of h_s and signal values less the chart's offset (ChartProvider::gather).
template <class T>
struct Arrays {
  const T *x, *y, *weight, *value;
  size_t stride;
};

inline Arrays<double> arrays(const Chart& chart, const Samples& s, double) {
  return {chart.x.data(), chart.y.data(), s.weight.data(), s.value.data(), s.stride};
}
inline Arrays<float> arrays(const Chart&, const Samples& s, float) {
  return {s.fx.data(), s.fy.data(), s.fweight.data(), s.fvalue.data(), s.stride};
}

// Adds one vector of entries starting at the arrays given to the sums, those of the lanes in `lanes`.
template <class T, int W, class Range>
[[gnu::always_inline]] inline void addLanes(const T* x, const T* y, const T* weight, const T* value, size_t stride,
                                            typename Lanes<T>::Vec qx, typename Lanes<T>::Vec qy, T invTwoHs2, T r2,
                                            const Range& range, bool joint, typename Lanes<T>::Bits lanes,
                                            Sums<T>& sums) {
  using Vec = typename Lanes<T>::Vec;
  using Bits = typename Lanes<T>::Bits;
  constexpr T kMax = Range::kBase2 ? Lanes<T>::kMaxExponent2 : Lanes<T>::kMaxExponent;
  const Vec dx = load(x) - qx, dy = load(y) - qy, d2 = dx * dx + dy * dy;
  Bits keep;
  Vec a;
  if constexpr (Range::kBase2)
    a = d2 + range(value, stride, keep);  // coordinates scaled so that d2 is the exponent (gather)
  else
    a = d2 * invTwoHs2 + range(value, stride, keep);
  const Vec clamped = a < kMax ? a : Vec{} + kMax;
  Vec k;
  if constexpr (Range::kBase2)
    k = load(weight) * exp2Negative(clamped);
  else
    k = load(weight) * expNegative(clamped);
  const Vec w = select<T>(lanes & keep & (d2 <= r2) & (a < kMax), k);
  sums.sw += w;
  sums.mx += w * dx;
  sums.my += w * dy;
  if (joint)
    for (int d = 0; d < W; ++d) sums.acc[d] += w * load(value + d * stride);
}

// Adds the entries [begin, end); W joint Euclidean dimensions accumulate when `joint`.
template <class T, int W, class Range>
[[gnu::always_inline]] inline void addRun(const Arrays<T>& in, int begin, int end, T qx, T qy, T invTwoHs2, T r2,
                                          const Range& range, bool joint, Sums<T>& sums) {
  using Bits = typename Lanes<T>::Bits;
  constexpr int N = Lanes<T>::N;
  const size_t stride = in.stride;
  const auto vx = typename Lanes<T>::Vec{} + qx, vy = typename Lanes<T>::Vec{} + qy;
  const Bits all = Bits{} - 1;
  int e = begin;
  for (; e + N <= end; e += N)
    addLanes<T, W>(in.x + e, in.y + e, in.weight + e, in.value + e, stride, vx, vy, invTwoHs2, r2, range, joint, all,
                   sums);
  if (e < end) {
    // The last entries: a whole vector read on (the arrays are padded by a vector of finite
    // values), the lanes past the run's end masked out.
    Bits lane;
    for (int i = 0; i < N; ++i) lane[i] = i;
    addLanes<T, W>(in.x + e, in.y + e, in.weight + e, in.value + e, stride, vx, vy, invTwoHs2, r2, range, joint,
                   lane < (end - e), sums);
  }
  flushRun<W>(sums, joint);
}

// The sums of an iteration at (qx, qy); for single precision, the coordinates are scaled by
// `unit` (1/h_s, or kSpatialScale/h_s for base-2 exponents) and rounded, and the step is corrected
// by what the rounding moved the iterate.
template <class T, int W, class Range>
[[gnu::always_inline]] inline void addChart(const Chart& chart, const Samples& samples, double qx, double qy,
                                            const Setup& s, const Range& range, Totals& totals) {
  const double unit = !std::is_same_v<T, float> ? 1.0 : (Range::kBase2 ? kSpatialScale : 1.0) / s.hs;
  const Arrays<T> in = arrays(chart, samples, T{});
  const T tx = static_cast<T>(qx * unit), ty = static_cast<T>(qy * unit);
  const T invTwoHs2 = static_cast<T>(s.invTwoHs2 / (unit * unit)), r2 = static_cast<T>(s.r2 * unit * unit);
  Sums<T> sums;
  forEachRun(chart, qx, qy, s.r, [&](int begin, int end) {
    addRun<T, W>(in, begin, end, tx, ty, invTwoHs2, r2, range, s.joint, sums);
  });
  totals.sw = total<T>(sums.sw, sums.dsw);
  // Σw(x − q) = Σw(x − t) + (t − q)Σw, back in chart units.
  totals.mx = (total<T>(sums.mx, sums.dmx) + (double(tx) - qx * unit) * totals.sw) / unit;
  totals.my = (total<T>(sums.my, sums.dmy) + (double(ty) - qy * unit) * totals.sw) / unit;
  for (int d = 0; d < W; ++d)
    totals.acc[d] = total<T>(sums.acc[d], sums.dacc[d]) / samples.scale[d] + samples.offset[d] * totals.sw;
}

template <class T, int W>
void addGaussian(const Chart& chart, const Samples& samples, double qx, double qy, const Setup& s,
                 const double* value, Totals& totals) {
  GaussianRange<T, W> range;
  for (int d = 0; d < W; ++d) {
    range.y[d] = static_cast<T>((value[d] - samples.offset[d]) * samples.scale[d]);
    range.coef[d] = static_cast<T>(s.coef[d]);
  }
  addChart<T, W>(chart, samples, qx, qy, s, range, totals);
}

}  // namespace

constexpr size_t kPad = 8;  // entries: one vector of either precision

void ChartProvider::gather(Samples& samples, const Chart& chart, const std::vector<double>& signal) const {
  const size_t n = chart.vertex.size();
  const int width = s_.width;
  samples.stride = n;
  // Each array is padded by a vector of zeros for the masked tails of addRun.
  if (!s_.singlePrecision) {
    samples.weight.assign(n + kPad, 0.0);
    samples.value.assign(n * width + kPad, 0.0);
    for (size_t e = 0; e < n; ++e) {
      const int v = chart.vertex[e];
      samples.weight[e] = s_.sampleWeight[v];
      const double* row = &signal[static_cast<size_t>(v) * width];
      for (int d = 0; d < width; ++d) samples.value[d * n + e] = row[d];
    }
    return;
  }
  // Single precision: values less their mean over the chart (differences keep their digits however
  // far the signal sits from 0), weights over their mean, coordinates in units of h_s; for Gaussian
  // loops values and coordinates scaled so that their squared differences are the kernel's
  // exponent in base 2.
  std::fill(std::begin(samples.offset), std::end(samples.offset), 0.0);
  std::fill(std::begin(samples.scale), std::end(samples.scale), 1.0);
  if (s_.loop == Setup::Loop::Gaussian) {
    for (int d = 0; d < width; ++d) samples.scale[d] = std::sqrt(s_.coef[d] * kLog2e);
    if (n > 0) {
      for (size_t e = 0; e < n; ++e)
        for (int d = 0; d < width; ++d) samples.offset[d] += signal[static_cast<size_t>(chart.vertex[e]) * width + d];
      for (int d = 0; d < width; ++d) samples.offset[d] /= static_cast<double>(n);
    }
  }
  const double unit = (s_.loop == Setup::Loop::Gaussian ? kSpatialScale : 1.0) / s_.hs;
  samples.fx.assign(n + kPad, 0.0f);
  samples.fy.assign(n + kPad, 0.0f);
  samples.fweight.assign(n + kPad, 0.0f);
  samples.fvalue.assign(n * width + kPad, 0.0f);
  for (size_t e = 0; e < n; ++e) {
    const int v = chart.vertex[e];
    samples.fx[e] = static_cast<float>(chart.x[e] * unit);
    samples.fy[e] = static_cast<float>(chart.y[e] * unit);
    samples.fweight[e] = static_cast<float>(s_.sampleWeight[v] * s_.weightScale);
    const double* row = &signal[static_cast<size_t>(v) * width];
    for (int d = 0; d < width; ++d)
      samples.fvalue[d * n + e] = static_cast<float>((row[d] - samples.offset[d]) * samples.scale[d]);
  }
}

namespace {

// The loop for the setup's channel set (makeSetup chooses Gaussian only for up to 4 dimensions).
template <class T>
[[gnu::always_inline]] inline void sumsIn(const Setup& s, const Chart& chart, const Samples& samples,
                                          double qx, double qy, const double* y, Totals& totals) {
  switch (s.loop) {
    case Setup::Loop::Gaussian:
      switch (s.width) {
        case 1: addGaussian<T, 1>(chart, samples, qx, qy, s, y, totals); break;
        case 2: addGaussian<T, 2>(chart, samples, qx, qy, s, y, totals); break;
        case 3: addGaussian<T, 3>(chart, samples, qx, qy, s, y, totals); break;
        default: addGaussian<T, 4>(chart, samples, qx, qy, s, y, totals); break;
      }
      break;
    case Setup::Loop::Similarity: {
      const SimilarityRange<T> range{{T(y[0]), T(y[1]), T(y[2])}, T(s.channels.front().invTwoHr2)};
      addChart<T, 0>(chart, samples, qx, qy, s, range, totals);
      break;
    }
    case Setup::Loop::General: break;  // never called: Climber::generalSums
  }
}

[[gnu::always_inline]] inline void sums(const Setup& s, const Chart& chart, const Samples& samples, double qx,
                                        double qy, const double* y, Totals& totals) {
  if (s.singlePrecision)
    sumsIn<float>(s, chart, samples, qx, qy, y, totals);
  else
    sumsIn<double>(s, chart, samples, qx, qy, y, totals);
}

// The same loop compiled for the baseline instruction set and, on x86-64, for AVX2 (a vector in one
// register instead of two), chosen at run time. Both do the same IEEE operations on every entry and
// add in the same lanes (AVX2 alone brings no fused multiply-add), so their results are identical.
[[gnu::flatten]] void sumsBaseline(const Setup& s, const Chart& chart, const Samples& samples, double qx,
                                   double qy, const double* y, Totals& totals) {
  sums(s, chart, samples, qx, qy, y, totals);
}

#if defined(__x86_64__) && defined(__GNUC__)
[[gnu::flatten, gnu::target("avx2")]] void sumsAvx2(const Setup& s, const Chart& chart,
                                                     const Samples& samples, double qx, double qy,
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

#include "geoshift/noise.hpp"

#include <cmath>
#include <random>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift {
namespace {

// Natural logarithm from +, −, ×, ÷ and frexp only. libm's log differs in the last bit between
// glibc (native) and musl (Emscripten), and a one-ulp difference in one draw would make the noisy
// mesh, and every figure measured on it, differ between the CLI and the web app.
double portableLog(double x) {
  int e = 0;
  double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1): exact
  constexpr double kSqrtHalf = 0.70710678118654752440;
  if (m < kSqrtHalf) {
    m *= 2.0;
    --e;
  }
  // log m = 2 atanh(f) with f = (m − 1)/(m + 1), |f| <= 0.1716: the series Σ f^(2k+1)/(2k+1)
  // reaches double precision after 12 terms.
  const double f = (m - 1.0) / (m + 1.0);
  const double f2 = f * f;
  double series = 0.0;
  for (int k = 12; k >= 0; --k) series = 1.0 / (2 * k + 1) + f2 * series;
  constexpr double kLn2 = 0.69314718055994530942;
  return e * kLn2 + 2.0 * f * series;
}

// mt19937_64's raw output is fixed by the standard; the distributions are not, so the transforms
// below are our own.
class Sampler {
 public:
  explicit Sampler(std::uint64_t seed) : engine_(seed) {}

  // Top 53 bits: every double in [0, 1) with spacing 2^-53, no rounding up to 1.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  // Marsaglia's polar form of Box–Muller: needs only log and sqrt (sqrt is exact in IEEE 754), no
  // sine or cosine. The second value of each pair is kept for the next call.
  double normal() {
    if (hasSpare_) {
      hasSpare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double factor = std::sqrt(-2.0 * portableLog(s) / s);
    spare_ = v * factor;
    hasSpare_ = true;
    return u * factor;
  }

  // Uniform on the sphere: an isotropic Gaussian vector, normalised.
  Vec3 direction() {
    for (;;) {
      // Three statements, not three arguments: argument order is unspecified (g++ and em++ differ).
      const double gx = normal();
      const double gy = normal();
      const double gz = normal();
      const Vec3 g(gx, gy, gz);
      const double len = g.norm();
      if (len > 1e-12) return g / len;
    }
  }

 private:
  std::mt19937_64 engine_;
  bool hasSpare_ = false;
  double spare_ = 0.0;
};

}  // namespace

std::vector<Vec3> addNoise(Mesh& mesh, const NoiseOptions& options) {
  if (!(options.amount >= 0) || !std::isfinite(options.amount)) {
    throw InputError("noise amount must be a finite number >= 0 (got " +
                     std::to_string(options.amount) + ")");
  }
  if (options.distribution == NoiseDistribution::Impulsive &&
      !(options.impulseFraction > 0 && options.impulseFraction <= 1)) {
    throw InputError("noise impulse fraction must be in (0, 1] (got " + std::to_string(options.impulseFraction) + ")");
  }
  const double scale = options.amount * averageEdgeLength(mesh);
  std::vector<Vec3> normals;
  if (options.direction == NoiseDirection::Normal) normals = vertexNormals(mesh);

  Sampler sampler(options.seed);
  std::vector<Vec3> displacement(mesh.vertexCount(), Vec3::Zero());
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    // Isolated vertices draw nothing, so the noise on the surface does not depend on them.
    if (mesh.isIsolated(v)) continue;
    if (options.distribution == NoiseDistribution::Impulsive && !(sampler.uniform() < options.impulseFraction)) continue;
    const bool alongNormal = options.direction == NoiseDirection::Normal;
    const Vec3 dir = alongNormal ? normals[v] : sampler.direction();
    double magnitude = scale;
    switch (options.distribution) {
      case NoiseDistribution::Fixed: break;
      case NoiseDistribution::Uniform: magnitude = scale * sampler.uniform(); break;
      case NoiseDistribution::Gaussian:
      case NoiseDistribution::Impulsive: magnitude = scale * sampler.normal(); break;
    }
    // A magnitude that is never negative along the normal needs a sign of its own.
    const bool unsignedMagnitude =
        options.distribution == NoiseDistribution::Fixed || options.distribution == NoiseDistribution::Uniform;
    if (alongNormal && unsignedMagnitude && sampler.uniform() < 0.5) magnitude = -magnitude;
    displacement[v] = magnitude * dir;
    mesh.position(v) += displacement[v];
  }
  return displacement;
}

}  // namespace geoshift

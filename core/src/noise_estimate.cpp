// estimateNoise (noise.hpp; docs/denoising.md#noise-estimate).
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"

namespace geoshift {

namespace {

// Vertices within two edges of v (v first), as mesh indices; `mark` is a scratch stamp array.
void twoRing(const Mesh& mesh, int v, std::vector<int>& mark, int stamp, std::vector<int>& out) {
  out.clear();
  out.push_back(v);
  mark[v] = stamp;
  for (size_t i = 0, ringEnd = 1; i < ringEnd && out.size() < 200; ++i) {
    mesh.forEachOutgoing(out[i], [&](int h) {
      for (int w : {mesh.head(h), mesh.tail(Mesh::prev(h))}) {
        if (mark[w] != stamp) {
          mark[w] = stamp;
          out.push_back(w);
        }
      }
    });
    if (i == 0) ringEnd = out.size();  // after the one-ring, expand each of its vertices once
  }
}

// Residual variance of a quadric fit to the points around v, or -1 when the fit is not usable.
double localVariance(const Mesh& mesh, const std::vector<int>& ring) {
  const int m = static_cast<int>(ring.size());
  if (m < 9) return -1;
  Vec3 centre = Vec3::Zero();
  for (int w : ring) centre += mesh.position(w);
  centre /= m;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int w : ring) {
    const Vec3 d = mesh.position(w) - centre;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.compute(cov);
  const Vec3 n = eig.eigenvectors().col(0), u = eig.eigenvectors().col(2), t = eig.eigenvectors().col(1);
  // Height z over (x, y) in the plane's frame, centred on v: z = a x² + b xy + c y² + d x + e y + f.
  constexpr int p = 6;
  Eigen::Matrix<double, p, p> ata = Eigen::Matrix<double, p, p>::Zero();
  Eigen::Matrix<double, p, 1> atz = Eigen::Matrix<double, p, 1>::Zero();
  const Vec3 origin = mesh.position(ring[0]);
  double scale = 0;
  for (int w : ring) scale = std::max(scale, (mesh.position(w) - origin).norm());
  if (!(scale > 0)) return -1;
  std::vector<Eigen::Matrix<double, p, 1>> rows(m);
  std::vector<double> zs(m);
  for (int i = 0; i < m; ++i) {
    const Vec3 d = (mesh.position(ring[i]) - origin) / scale;
    const double x = d.dot(u), y = d.dot(t), z = d.dot(n);
    rows[i] << x * x, x * y, y * y, x, y, 1;
    zs[i] = z;
    ata += rows[i] * rows[i].transpose();
    atz += rows[i] * z;
  }
  Eigen::LDLT<Eigen::Matrix<double, p, p>> ldlt;
  ldlt.compute(ata);
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-10)) return -1;
  const Eigen::Matrix<double, p, 1> coef = ldlt.solve(atz);
  double sum = 0;
  for (int i = 0; i < m; ++i) {
    const double r = zs[i] - rows[i].dot(coef);
    sum += r * r;
  }
  // Σ r² has expectation σ²(m − p) for a least-squares fit of p parameters.
  return sum / (m - p) * scale * scale;
}

}  // namespace

std::vector<int> noiseSampleVertices(const Mesh& mesh, int maxSamples) {
  std::vector<int> out;
  const int n = mesh.vertexCount();
  if (mesh.faceCount() == 0 || n == 0 || maxSamples < 1) return out;
  const int stride = std::max(1, (n + maxSamples - 1) / maxSamples);
  for (int v = 0; v < n; v += stride)
    if (!mesh.isIsolated(v) && !mesh.isBoundaryVertex(v)) out.push_back(v);
  return out;
}

std::vector<double> quadricResidualVariances(const Mesh& mesh, const std::vector<int>& vertices) {
  std::vector<int> mark(mesh.vertexCount(), -1), ring;
  std::vector<double> out;
  out.reserve(vertices.size());
  for (int v : vertices) {
    twoRing(mesh, v, mark, v, ring);
    const double var = localVariance(mesh, ring);
    out.push_back(var >= 0 && std::isfinite(var) ? var : -1.0);
  }
  return out;
}

NoiseEstimate estimateNoise(const Mesh& mesh, int maxSamples) {
  NoiseEstimate out;
  const std::vector<double> all = quadricResidualVariances(mesh, noiseSampleVertices(mesh, maxSamples));
  std::vector<double> variances;
  for (double v : all)
    if (v >= 0) variances.push_back(v);
  if (variances.empty()) return out;
  const double ael = averageEdgeLength(mesh);
  std::sort(variances.begin(), variances.end());
  // The lower half of the per-vertex variances: vertices on creases and corners, whose quadric fit
  // fails, sit in the upper half on any mesh that is not mostly crease. For Gaussian residuals a
  // vertex's estimate is σ² χ²_k / k with k = m − 6 ≈ 13 on a regular two-ring, and the mean of the
  // lower half of that is 0.69 σ² (docs/denoising.md#noise-estimate has the figures).
  const size_t keep = std::max<size_t>(1, variances.size() / 2);
  double sum = 0;
  for (size_t i = 0; i < keep; ++i) sum += variances[i];
  out.absolute = std::sqrt(sum / keep / 0.69);
  out.level = out.absolute / ael;
  double total = sum;
  for (size_t i = keep; i < variances.size(); ++i) total += variances[i];
  out.upperLevel = std::sqrt(total / variances.size()) / ael;
  out.samples = static_cast<int>(variances.size());
  return out;
}

}  // namespace geoshift

// estimateNoise (noise.hpp; docs/denoising.md#noise-estimate).
#include <algorithm>
#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

#include <Eigen/Dense>

#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/smoothing.hpp"

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

HighFrequencyNoise highFrequencyNoise(const Mesh& mesh, const ParallelOptions& parallel) {
  // docs/denoising.md#noise-estimate. Two applications of the uniform Laplacian L (each vertex less
  // the mean of its neighbours) take a smooth surface, curvature included, to about zero and keep
  // the noise's top frequencies; along the normals n of a smoothed copy, (L²y)·n over the vertices
  // away from creases and boundaries, against Σ (L²b)² for white noise b of unit variance, is the
  // noise variance along the normals.
  constexpr int kPower = 2, kProbes = 8, kSupportSteps = 10;
  constexpr double kCreaseDegrees = 30;
  const int nv = mesh.vertexCount();
  if (nv == 0 || mesh.faceCount() == 0) return {};
  Mesh support = mesh;
  TaubinOptions taubin;
  taubin.iterations = kSupportSteps;
  taubin.parallel = parallel;
  taubinSmooth(support, taubin);
  const std::vector<Vec3> normal = vertexNormals(support);

  // Neighbours, flattened (the order of Mesh::neighbors).
  std::vector<int> first(nv + 1, 0), adjacent;
  adjacent.reserve(static_cast<size_t>(mesh.halfedgeCount()) + nv);
  for (int v = 0; v < nv; ++v) {
    for (int w : mesh.neighbors(v)) adjacent.push_back(w);
    first[v + 1] = static_cast<int>(adjacent.size());
  }

  // Left out: within kPower + 1 rings of a boundary, an isolated vertex or a crease of the copy.
  std::vector<char> out(nv, 0);
  {
    const std::vector<Vec3> faceNormal = faceNormals(support);
    const double creaseCos = std::cos(kCreaseDegrees * 3.14159265358979323846 / 180);
    for (int v = 0; v < nv; ++v) out[v] = mesh.isIsolated(v);
    for (int h = 0; h < mesh.halfedgeCount(); ++h) {
      const int o = mesh.twin(h);
      if (o < 0 || faceNormal[Mesh::faceOf(h)].dot(faceNormal[Mesh::faceOf(o)]) < creaseCos)
        out[mesh.tail(h)] = out[mesh.head(h)] = 1;
    }
    for (int ring = 0; ring <= kPower; ++ring) {
      std::vector<char> grown = out;
      for (int v = 0; v < nv; ++v)
        if (out[v])
          for (int i = first[v]; i < first[v + 1]; ++i) grown[adjacent[i]] = 1;
      out.swap(grown);
    }
  }

  const Progress quiet;
  auto laplacian = [&](const auto& x) {
    std::remove_cvref_t<decltype(x)> y(x.size());
    parallelFor(nv, parallel, quiet, "", 0, 1, [&](int v, int) {
      const int n = first[v + 1] - first[v];
      if (n == 0) {
        y[v] = x[v] - x[v];
        return;
      }
      auto sum = x[adjacent[first[v]]];
      for (int i = first[v] + 1; i < first[v + 1]; ++i) sum = sum + x[adjacent[i]];
      y[v] = x[v] - sum * (1.0 / n);
    });
    return y;
  };

  std::vector<Vec3> high = mesh.positions();
  for (int k = 0; k < kPower; ++k) high = laplacian(high);
  // Σ over probes of (L²b)² per vertex: the operator's response to white noise there.
  std::vector<double> response(nv, 0.0);
  std::mt19937_64 random(0x6e6f697365ull);
  for (int p = 0; p < kProbes; ++p) {
    std::vector<double> b(nv);
    for (double& e : b) e = (random() >> 63) ? 1.0 : -1.0;
    for (int k = 0; k < kPower; ++k) b = laplacian(b);
    for (int v = 0; v < nv; ++v) response[v] += b[v] * b[v];
  }
  double measured = 0, fourth = 0, expected = 0;
  int count = 0;
  for (int v = 0; v < nv; ++v) {
    if (out[v] || normal[v].squaredNorm() == 0) continue;
    const double d = high[v].dot(normal[v]);
    measured += d * d;
    fourth += d * d * d * d;
    expected += response[v] / kProbes;
    ++count;
  }
  if (!(expected > 0) || !(measured > 0)) return {};
  const double meanSquare = measured / count;
  return {std::sqrt(measured / expected) / averageEdgeLength(mesh), fourth / count / (meanSquare * meanSquare), count};
}

double highFrequencyNoiseLevel(const Mesh& mesh, const ParallelOptions& parallel) {
  return highFrequencyNoise(mesh, parallel).level;
}

std::vector<double> planarResiduals(const Mesh& mesh, const std::vector<Vec3>& positions, double* confirmedShare,
                                    std::vector<char>* confirmedFaces, std::vector<char>* inPlane) {
  // docs/denoising.md#noise-estimate ("Planes left untouched").
  constexpr double kSameDegrees = 1;
  const int nv = mesh.vertexCount(), nf = mesh.faceCount();
  std::vector<double> residual(nv, -1.0);
  if (confirmedShare) *confirmedShare = 0;
  if (nv == 0 || nf == 0) return residual;
  std::vector<Vec3> normal(nf);
  for (int f = 0; f < nf; ++f) {
    const Face& c = mesh.face(f);
    const Vec3 n = (positions[c[1]] - positions[c[0]]).cross(positions[c[2]] - positions[c[0]]);
    const double length = n.norm();
    normal[f] = length > 0 ? Vec3(n / length) : Vec3::Zero();
  }
  const double sameCos = std::cos(kSameDegrees * 3.14159265358979323846 / 180);
  std::vector<char> confirmed(nf, 0);
  int count = 0;
  for (int f = 0; f < nf; ++f) {
    if (normal[f].squaredNorm() == 0) continue;
    for (int k = 0; k < 3 && !confirmed[f]; ++k) {
      const int o = mesh.twin(3 * f + k);
      if (o >= 0 && normal[f].dot(normal[Mesh::faceOf(o)]) >= sameCos) confirmed[f] = 1;
    }
    count += confirmed[f];
  }
  if (confirmedShare) *confirmedShare = static_cast<double>(count) / nf;
  if (confirmedFaces) *confirmedFaces = confirmed;
  if (inPlane) {
    // v lies in the plane of the face across the edge opposite it in one of its faces.
    inPlane->assign(nv, 0);
    for (int f = 0; f < nf; ++f) {
      if (normal[f].squaredNorm() == 0) continue;
      for (int k = 0; k < 3; ++k) {
        const int o = mesh.twin(3 * f + (k + 1) % 3);
        if (o >= 0 && normal[f].dot(normal[Mesh::faceOf(o)]) >= sameCos) (*inPlane)[mesh.face(f)[k]] = 1;
      }
    }
  }
  if (count == 0) return residual;
  for (int v = 0; v < nv; ++v) {
    if (mesh.isIsolated(v)) continue;
    const Vec3& y = positions[v];
    double nearest = -1;
    // The faces around each neighbour: v's two-ring.
    for (int u : mesh.neighbors(v)) {
      mesh.forEachOutgoing(u, [&](int h) {
        const int f = Mesh::faceOf(h);
        if (!confirmed[f]) return;
        const Face& c = mesh.face(f);
        if (c[0] == v || c[1] == v || c[2] == v) return;
        const double d = std::abs((y - positions[c[0]]).dot(normal[f]));
        if (nearest < 0 || d < nearest) nearest = d;
      });
    }
    residual[v] = nearest;
  }
  return residual;
}

PlanarNoise planarNoise(const Mesh& mesh) {
  PlanarNoise out;
  const std::vector<double> residual = planarResiduals(mesh, mesh.positions(), &out.confirmedShare);
  double sum = 0;
  for (double r : residual)
    if (r >= 0) {
      sum += r * r;
      ++out.samples;
    }
  if (out.samples > 0) out.level = std::sqrt(sum / out.samples) / averageEdgeLength(mesh);
  return out;
}

}  // namespace geoshift

#include "geoshift/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/parallel.hpp"

namespace geoshift {
namespace {

// Who each vertex averages, fixed for the whole call (connectivity does not change). For an interior
// vertex one entry per outgoing half-edge, with the two vertices opposite that edge (for the
// cotangent weights only); for a boundary vertex its two boundary neighbours only, without opposites.
// Sized exactly: a denoise smooths while its largest arrays are held (docs/denoising.md#speed-and-memory).
struct Stencil {
  std::vector<int> start;  // vertex v's entries are [start[v], start[v+1])
  std::vector<int> neighbor;
  std::vector<int> oppositeA, oppositeB;  // cotangent weights only; -1 on boundary stencils
  std::vector<char> boundary;
};

Stencil buildStencil(const Mesh& mesh, bool opposites) {
  Stencil s;
  const int n = mesh.vertexCount();
  s.start.assign(n + 1, 0);
  s.boundary.assign(n, 0);
  // Entries: the outgoing half-edges of interior vertices, two for each boundary vertex.
  size_t entries = 0;
  for (int v = 0; v < n; ++v) {
    if (mesh.isIsolated(v)) continue;
    if (mesh.isBoundaryVertex(v)) {
      entries += 2;
    } else {
      mesh.forEachOutgoing(v, [&](int) { ++entries; });
    }
  }
  s.neighbor.reserve(entries);
  if (opposites) {
    s.oppositeA.reserve(entries);
    s.oppositeB.reserve(entries);
  }
  const auto add = [&](int nb, int a, int b) {
    s.neighbor.push_back(nb);
    if (!opposites) return;
    s.oppositeA.push_back(a);
    s.oppositeB.push_back(b);
  };
  for (int v = 0; v < n; ++v) {
    s.start[v] = static_cast<int>(s.neighbor.size());
    if (mesh.isIsolated(v)) continue;
    if (mesh.isBoundaryVertex(v)) {
      // vcglib's AccumulateLaplacianInfo: a border vertex only listens to the border, so open
      // borders shrink as a 1D polyline instead of being pulled into the surface.
      s.boundary[v] = 1;
      int last = -1;
      mesh.forEachOutgoing(v, [&](int h) { last = h; });
      for (int nb : {mesh.head(mesh.halfedge(v)), mesh.tail(Mesh::prev(last))}) add(nb, -1, -1);
      continue;
    }
    mesh.forEachOutgoing(v, [&](int h) {
      add(mesh.head(h), mesh.tail(Mesh::prev(h)), mesh.tail(Mesh::prev(mesh.twin(h))));
    });
  }
  s.start[n] = static_cast<int>(s.neighbor.size());
  return s;
}

double cotAt(const Vec3& corner, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - corner, w = b - corner;
  const double c = u.cross(w).norm();
  return c > 0 ? u.dot(w) / c : 0.0;
}

// Δx_v = Σ_j w_vj (x_j − x_v) with Σ_j w_vj = 1 (Taubin 1995, eq. 4).
Vec3 laplacianAt(const std::vector<Vec3>& x, const Stencil& s, LaplacianWeights weights, int v) {
  const int begin = s.start[v], end = s.start[v + 1];
  Vec3 sum = Vec3::Zero();
  double total = 0;
  for (int e = begin; e < end; ++e) {
    const Vec3 d = x[s.neighbor[e]] - x[v];
    double w = 1.0;
    if (weights != LaplacianWeights::Uniform) {
      const double len = d.norm();
      // A boundary stencil is a 1D polyline, whose cotangent Laplacian is 1/|e| as well.
      if (weights == LaplacianWeights::Fujiwara || s.boundary[v]) {
        w = len > 0 ? 1.0 / len : 0.0;
      } else {
        // (cot α + cot β) / 2, clamped at 0: negative weights across obtuse triangles make the
        // normalised step leave the convex hull of the ring and can flip triangles.
        const Vec3& xj = x[s.neighbor[e]];
        w = std::max(0.0, 0.5 * (cotAt(x[s.oppositeA[e]], x[v], xj) + cotAt(x[s.oppositeB[e]], x[v], xj)));
      }
    }
    sum += w * d;
    total += w;
  }
  if (total > 0 && std::isfinite(total)) return sum / total;
  if (end == begin) return Vec3::Zero();  // isolated vertex: does not move
  // All weights vanished (a collapsed ring): fall back to the umbrella operator.
  Vec3 mean = Vec3::Zero();
  for (int e = begin; e < end; ++e) mean += x[s.neighbor[e]] - x[v];
  return mean / static_cast<double>(end - begin);
}

// laplacianAt for uniform weights, to the bit: the same differences summed in the same order and
// divided by their count (a sum of ones is exact), without the test of the weights per neighbour and
// with x and y side by side in one register (GCC/Clang vector extensions: SSE2 natively, wasm SIMD in
// the browser; each lane runs the scalar code's operations in its order). 0.6 of laplacianAt's time
// for the Taubin steps that are most of a denoise's smoothing (docs/denoising.md#speed-and-memory).
Vec3 uniformLaplacianAt(const std::vector<Vec3>& x, const Stencil& s, int v) {
  using Double2 = double __attribute__((vector_size(16)));
  const auto xyOf = [](const Vec3& p) {
    Double2 xy;
    std::memcpy(&xy, p.data(), sizeof xy);
    return xy;
  };
  const int begin = s.start[v], end = s.start[v + 1];
  if (end == begin) return Vec3::Zero();
  const Vec3& xv = x[v];
  const Double2 xy = xyOf(xv);
  const double z = xv.z();
  const int* neighbor = s.neighbor.data();
  Double2 sumXy = {0.0, 0.0};
  double sumZ = 0.0;
  for (int e = begin; e < end; ++e) {
    const Vec3& p = x[neighbor[e]];
    sumXy += xyOf(p) - xy;
    sumZ += p.z() - z;
  }
  const double count = end - begin;
  sumXy /= count;
  return Vec3(sumXy[0], sumXy[1], sumZ / count);
}

}  // namespace

void taubinSmooth(Mesh& mesh, const TaubinOptions& options, const Progress& progress) {
  requireAtLeast("Taubin: iterations", options.iterations, 0);
  requirePositive("Taubin: lambda", options.lambda);
  // μ < −λ < 0 makes the pass-band k_PB = 1/λ + 1/μ positive: the low frequencies pass and the
  // mesh does not shrink (Taubin 1995, section 4).
  if (!(options.mu < -options.lambda) || !std::isfinite(options.mu)) {
    throw InputError("Taubin: mu must be < -lambda (got mu " + formatNumber(options.mu) + ", lambda " +
                     formatNumber(options.lambda) + ")");
  }
  const Stencil stencil = buildStencil(mesh, options.weights == LaplacianWeights::Cotangent);
  // Work on a copy: a cancelled call must leave the mesh as it was. Each half-step writes the
  // next positions into the other buffer, vertex by vertex (in parallel: each vertex reads only the
  // previous positions, so the result does not depend on the threads).
  std::vector<Vec3> x = mesh.positions(), next(x.size());
  ParallelOptions par = options.parallel;
  par.chunk = 1024;
  const int n = static_cast<int>(x.size());
  for (int it = 0; it < options.iterations; ++it) {
    progress.step(static_cast<double>(it) / options.iterations, "taubin");
    for (double factor : {options.lambda, options.mu}) {
      if (options.weights == LaplacianWeights::Uniform)
        parallelFor(n, par, Progress{}, "", 0, 1,
                    [&](int v, int) { next[v] = x[v] + factor * uniformLaplacianAt(x, stencil, v); });
      else
        parallelFor(n, par, Progress{}, "", 0, 1,
                    [&](int v, int) { next[v] = x[v] + factor * laplacianAt(x, stencil, options.weights, v); });
      x.swap(next);
    }
  }
  progress.step(1.0, "taubin");
  mesh.positions() = std::move(x);
}

}  // namespace geoshift

// shapes::implicitSurface: the zero set of a field, marched on tetrahedra and relaxed.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "geoshift/error.hpp"
#include "geoshift/shapes.hpp"

namespace geoshift::shapes {
namespace {

Vec3 gradient(const ImplicitField& field, const Vec3& p, double step) {
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 d = Vec3::Zero();
    d[k] = step;
    g[k] = (field(p + d) - field(p - d)) / (2 * step);
  }
  return g;
}

// Newton steps onto the zero set along the gradient.
Vec3 project(const ImplicitField& field, Vec3 p, double step) {
  for (int i = 0; i < 4; ++i) {
    const Vec3 g = gradient(field, p, step);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12) break;
    p -= (field(p) / g2) * g;
  }
  return p;
}

}  // namespace

TriangleSoup implicitSurface(const ImplicitField& field, const Vec3& lo, const Vec3& hi, double h, int relaxPasses) {
  if (!(h > 0) || !lo.allFinite() || !hi.allFinite() || !((hi - lo).minCoeff() > 0)) {
    throw InputError("shapes: implicit surface needs a box lo < hi and a cell size > 0");
  }
  std::array<int, 3> dims;
  double cells = 1;
  for (int k = 0; k < 3; ++k) {
    dims[k] = static_cast<int>(std::ceil((hi[k] - lo[k]) / h)) + 1;  // points
    cells *= dims[k];
  }
  if (cells > 2e8) throw InputError("shapes: implicit surface grid of " + std::to_string(cells) + " points is too fine");
  auto id = [&](int i, int j, int k) { return (static_cast<std::int64_t>(k) * dims[1] + j) * dims[0] + i; };
  auto point = [&](std::int64_t g) {
    const int i = static_cast<int>(g % dims[0]), j = static_cast<int>(g / dims[0] % dims[1]),
              k = static_cast<int>(g / (static_cast<std::int64_t>(dims[0]) * dims[1]));
    return Vec3(lo.x() + i * h, lo.y() + j * h, lo.z() + k * h);
  };
  std::vector<double> value(static_cast<size_t>(dims[0]) * dims[1] * dims[2]);
  for (std::int64_t g = 0; g < static_cast<std::int64_t>(value.size()); ++g) {
    double f = field(point(g));
    // Keep every grid point strictly off the surface, so no crossing lands on a grid point and two
    // edges never make coincident vertices.
    if (std::abs(f) < 1e-9 * h) f = 1e-9 * h;
    value[g] = f;
  }

  TriangleSoup s;
  std::unordered_map<std::uint64_t, int> crossing;  // grid edge (a, b), a < b -> vertex
  auto edgeVertex = [&](std::int64_t a, std::int64_t b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = static_cast<std::uint64_t>(a) * value.size() + static_cast<std::uint64_t>(b);
    auto [it, inserted] = crossing.try_emplace(key, static_cast<int>(s.positions.size()));
    if (inserted) {
      const double t = value[a] / (value[a] - value[b]);
      s.positions.push_back(point(a) + t * (point(b) - point(a)));
    }
    return it->second;
  };
  auto emit = [&](int a, int b, int c, const Vec3& outward) {
    const Vec3 n = (s.positions[b] - s.positions[a]).cross(s.positions[c] - s.positions[a]);
    if (n.dot(outward) < 0) std::swap(b, c);
    s.faces.push_back({a, b, c});
  };
  // Freudenthal split of each cube into six tetrahedra around its 0-7 diagonal: neighbouring cubes
  // cut their shared square along the same diagonal, so the surface is closed.
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k + 1 < dims[2]; ++k)
    for (int j = 0; j + 1 < dims[1]; ++j)
      for (int i = 0; i + 1 < dims[0]; ++i)
        for (const auto& perm : perms) {
          std::array<int, 3> c = {i, j, k};
          std::array<std::int64_t, 4> tet;
          tet[0] = id(c[0], c[1], c[2]);
          for (int m = 0; m < 3; ++m) {
            ++c[perm[m]];
            tet[m + 1] = id(c[0], c[1], c[2]);
          }
          std::array<std::int64_t, 4> in, out;
          int ni = 0, no = 0;
          for (std::int64_t g : tet) (value[g] < 0 ? in[ni++] : out[no++]) = g;
          if (ni == 0 || no == 0) continue;
          Vec3 outward = Vec3::Zero();
          for (int a = 0; a < ni; ++a)
            for (int b = 0; b < no; ++b) outward += point(out[b]) - point(in[a]);
          if (ni == 1 || no == 1) {
            const std::int64_t apex = ni == 1 ? in[0] : out[0];
            const auto& others = ni == 1 ? out : in;
            emit(edgeVertex(apex, others[0]), edgeVertex(apex, others[1]), edgeVertex(apex, others[2]), outward);
          } else {
            // Two in, two out: the crossings form a quad in0-out0, in0-out1, in1-out1, in1-out0.
            const int q0 = edgeVertex(in[0], out[0]), q1 = edgeVertex(in[0], out[1]),
                      q2 = edgeVertex(in[1], out[1]), q3 = edgeVertex(in[1], out[0]);
            emit(q0, q1, q2, outward);
            emit(q0, q2, q3, outward);
          }
        }

  // Marching tetrahedra leaves slivers where the surface passes near grid points. Move every vertex
  // to the mean of its neighbours and back onto the surface a few times to even them out.
  std::vector<std::vector<int>> ring(s.positions.size());
  for (const Face& f : s.faces)
    for (int m = 0; m < 3; ++m) {
      ring[f[m]].push_back(f[(m + 1) % 3]);
      ring[f[m]].push_back(f[(m + 2) % 3]);
    }
  const double gradientStep = 1e-4 * h;
  for (int pass = 0; pass < relaxPasses; ++pass) {
    std::vector<Vec3> next(s.positions.size());
    for (size_t v = 0; v < s.positions.size(); ++v) {
      Vec3 mean = Vec3::Zero();
      for (int u : ring[v]) mean += s.positions[u];
      next[v] = project(field, mean / static_cast<double>(ring[v].size()), gradientStep);
    }
    s.positions = std::move(next);
  }
  return s;
}

}  // namespace geoshift::shapes

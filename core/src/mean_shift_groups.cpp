// Vertices grouped by cube for shared start charts.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

namespace {

constexpr int kLevels = 2;        // merged cubes of 2 and 4 times the cell's side
constexpr int kMaxMerged = 200;   // vertices: a merged group's climbs stay one prompt hand-out

struct Key {
  std::array<std::int64_t, 3> cube;  // of side setup.cell
  int vertex;
  // The cube of 2^level times the side that holds this one (>> rounds toward −inf).
  std::array<std::int64_t, 3> at(int level) const { return {cube[0] >> level, cube[1] >> level, cube[2] >> level}; }
};

}  // namespace

Groups groupVertices(const Setup& s) {
  const Mesh& mesh = s.mesh;
  const int n = mesh.vertexCount();
  Groups g;
  g.vertex.resize(n);
  g.of.resize(n);
  if (s.cell <= 0) {
    for (int v = 0; v < n; ++v) {
      g.start.push_back(v);
      g.vertex[v] = v;
      g.anchor.push_back(v);
      g.reach.push_back(0);
      g.of[v] = v;
    }
    g.start.push_back(n);
    return g;
  }
  std::vector<Key> keys(n);
  for (int v = 0; v < n; ++v) {
    const Vec3& p = mesh.position(v);
    const auto c = [&](int a) { return static_cast<std::int64_t>(std::floor(p[a] / s.cell)); };
    keys[v] = {{c(0), c(1), c(2)}, v};
  }
  // Sorted so that every cube of each level is one run of keys.
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    for (int level = kLevels; level >= 0; --level)
      if (a.at(level) != b.at(level)) return a.at(level) < b.at(level);
    return a.vertex < b.vertex;
  });
  for (int k = 0; k < n; ++k) g.vertex[k] = keys[k].vertex;

  // Gaussian curvature: interior angle defects (boundary vertices' turning says nothing about the
  // chart's metric) over vertex areas.
  const int levels = s.distortion > 0 ? kLevels : 0;
  const std::vector<double>& area = s.vertexAreas;
  std::vector<double> defect(n, 0.0);
  if (levels > 0) {
    for (int v = 0; v < n; ++v)
      if (!mesh.isIsolated(v) && !mesh.isBoundaryVertex(v)) defect[v] = 2 * std::numbers::pi - s.geometry.angleSum(v);
  }
  // The end of the run of cubes of `level` that starts at key i, within [i, last).
  const auto runEnd = [&](int i, int last, int level) {
    int j = i;
    while (j < last && keys[j].at(level) == keys[i].at(level)) ++j;
    return j;
  };
  // Whether the cube of `level` holding keys [a, b) is flat enough to share one chart: the mean
  // of |curvature| per cell-sized cube, times the farthest start and drift from its centre, squared.
  const auto flat = [&](int a, int b, int level) {
    if (b - a > kMaxMerged) return false;
    double total = 0, surface = 0;
    for (int i = a; i < b;) {
      const int j = runEnd(i, b, 0);
      double sum = 0;
      for (int k = i; k < j; ++k) {
        sum += defect[keys[k].vertex];
        surface += area[keys[k].vertex];
      }
      total += std::abs(sum);
      i = j;
    }
    const double reach = std::sqrt(3.0) * std::ldexp(s.cell, level) + s.drift;
    return surface > 0 && total / surface * reach * reach <= s.distortion;
  };
  std::vector<int> level;  // of each group
  const auto split = [&](auto&& self, int a, int b, int at) -> void {
    if (at == 0 || flat(a, b, at)) {
      g.start.push_back(a);
      level.push_back(at);
      return;
    }
    for (int i = a; i < b;) {
      const int j = runEnd(i, b, at - 1);
      self(self, i, j, at - 1);
      i = j;
    }
  };
  for (int i = 0; i < n;) {
    const int j = runEnd(i, n, levels);
    split(split, i, j, levels);
    i = j;
  }
  g.start.push_back(n);
  const int groups = static_cast<int>(g.start.size()) - 1;
  for (int i = 0; i < groups; ++i) {
    Vec3 centre = Vec3::Zero();
    for (int k = g.start[i]; k < g.start[i + 1]; ++k) centre += mesh.position(g.vertex[k]);
    centre /= g.start[i + 1] - g.start[i];
    int best = g.vertex[g.start[i]];
    for (int k = g.start[i]; k < g.start[i + 1]; ++k) {
      const int v = g.vertex[k];
      if ((mesh.position(v) - centre).squaredNorm() < (mesh.position(best) - centre).squaredNorm()) best = v;
    }
    g.anchor.push_back(best);
    for (int k = g.start[i]; k < g.start[i + 1]; ++k) g.of[g.vertex[k]] = i;
    // A vertex of the cube is at most its diagonal from the anchor; the geodesic can be longer,
    // and such a vertex then starts in its own chart.
    g.reach.push_back(std::sqrt(3.0) * std::ldexp(s.cell, level[i]));
  }
  return g;
}

}  // namespace geoshift::mean_shift_detail

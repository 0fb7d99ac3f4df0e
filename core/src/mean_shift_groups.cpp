// Vertices grouped by cube for shared start charts.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

Groups groupVertices(const Setup& s) {
  const Mesh& mesh = s.mesh;
  const int n = mesh.vertexCount();
  Groups g;
  g.vertex.resize(n);
  if (s.cell <= 0) {
    for (int v = 0; v < n; ++v) {
      g.start.push_back(v);
      g.vertex[v] = v;
      g.anchor.push_back(v);
    }
    g.start.push_back(n);
    return g;
  }
  using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t, int>;
  std::vector<Key> keys(n);
  for (int v = 0; v < n; ++v) {
    const Vec3& p = mesh.position(v);
    const auto c = [&](int a) { return static_cast<std::int64_t>(std::floor(p[a] / s.cell)); };
    keys[v] = {c(0), c(1), c(2), v};
  }
  std::sort(keys.begin(), keys.end());
  for (int k = 0; k < n; ++k) {
    g.vertex[k] = std::get<3>(keys[k]);
    const bool fresh = k == 0 || std::get<0>(keys[k]) != std::get<0>(keys[k - 1]) ||
                       std::get<1>(keys[k]) != std::get<1>(keys[k - 1]) || std::get<2>(keys[k]) != std::get<2>(keys[k - 1]);
    if (fresh) g.start.push_back(k);
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
  }
  return g;
}

}  // namespace geoshift::mean_shift_detail

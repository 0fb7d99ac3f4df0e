// Segmentation by modes (Comaniciu–Meer 2002, §4): vertices whose modes nearly coincide in space
// and in range are one segment.
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

namespace {

int findRoot(std::vector<int>& parent, int v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

// The smaller index becomes the root: the labelling below then does not depend on the order in
// which pairs were joined.
void join(std::vector<int>& parent, int a, int b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a == b) return;
  if (a < b) parent[b] = a;
  else parent[a] = b;
}

std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  // 21 bits an axis, wrapped: distinct nearby cells never collide, far ones may share a bucket
  // (the distance test below decides).
  return (static_cast<std::uint64_t>(x) & 0x1fffff) | (static_cast<std::uint64_t>(y) & 0x1fffff) << 21 |
         (static_cast<std::uint64_t>(z) & 0x1fffff) << 42;
}

}  // namespace

void segmentModes(const Setup& s, const std::vector<double>& signal, MeanShiftResult& result) {
  const int n = s.mesh.vertexCount();
  const double reach = 0.5 * s.hs, reach2 = reach * reach;
  std::vector<Vec3> at(n);
  std::vector<std::uint8_t> placed(n, 0);
  for (int v = 0; v < n; ++v)
    if (result.modes[v].face >= 0) {
      at[v] = result.modes[v].position(s.mesh);
      placed[v] = 1;
    }
  const auto closeInRange = [&](int a, int b) {
    for (const Channel& c : s.channels) {
      double d2 = 0;
      for (int d = c.offset; d < c.offset + c.dim; ++d) {
        const double x = signal[a * s.width + d] - signal[b * s.width + d];
        d2 += x * x;
      }
      if (d2 >= 0.25 * c.hr * c.hr) return false;
    }
    return true;
  };

  // Modes hashed into cells of side h_s/2: a partner is in the same or an adjacent cell.
  std::unordered_map<std::uint64_t, std::vector<int>> cells;
  const auto cellOf = [&](const Vec3& p, int a) { return static_cast<std::int64_t>(std::floor(p[a] / reach)); };
  for (int v = 0; v < n; ++v)
    if (placed[v]) cells[cellKey(cellOf(at[v], 0), cellOf(at[v], 1), cellOf(at[v], 2))].push_back(v);

  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int v = 0; v < n; ++v) {
    if (!placed[v]) continue;
    const std::int64_t cx = cellOf(at[v], 0), cy = cellOf(at[v], 1), cz = cellOf(at[v], 2);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find(cellKey(cx + dx, cy + dy, cz + dz));
          if (it == cells.end()) continue;
          for (int w : it->second)
            if (w > v && (at[w] - at[v]).squaredNorm() < reach2 && closeInRange(v, w)) join(parent, v, w);
        }
  }
  result.segment.assign(n, -1);
  result.segmentCount = 0;
  for (int v = 0; v < n; ++v) {
    const int root = findRoot(parent, v);
    if (result.segment[root] < 0) result.segment[root] = result.segmentCount++;
    result.segment[v] = result.segment[root];
  }
}

}  // namespace geoshift::mean_shift_detail

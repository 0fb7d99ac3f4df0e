#include "geoshift/shapes.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <unordered_map>

#include "geoshift/error.hpp"

namespace geoshift::shapes {
namespace {

// For the convex solids centred at the origin: turn every face so that its normal points away
// from the centre, rather than trusting a hand-written winding table.
void orientAwayFromOrigin(TriangleSoup& soup) {
  for (Face& f : soup.faces) {
    const Vec3& a = soup.positions[f[0]];
    const Vec3 n = (soup.positions[f[1]] - a).cross(soup.positions[f[2]] - a);
    if (n.dot(a + soup.positions[f[1]] + soup.positions[f[2]]) < 0) std::swap(f[1], f[2]);
  }
}

// Quads (i, j) -> (i+1, j) -> (i+1, j+1) -> (i, j+1) of a (u, v) parameter grid whose u runs
// counter-clockwise seen from outside relative to v, split along the (i, j)-(i+1, j+1) diagonal.
void addQuad(TriangleSoup& soup, int a, int b, int c, int d) {
  soup.faces.push_back({a, b, c});
  soup.faces.push_back({a, c, d});
}

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("shapes: " + what);
}

}  // namespace

TriangleSoup tetrahedron() {
  TriangleSoup s;
  const double k = 1.0 / std::sqrt(3.0);
  s.positions = {Vec3(k, k, k), Vec3(k, -k, -k), Vec3(-k, k, -k), Vec3(-k, -k, k)};
  s.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  orientAwayFromOrigin(s);
  return s;
}

TriangleSoup cube() {
  TriangleSoup s;
  for (int i = 0; i < 8; ++i) {
    s.positions.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
  }
  // Each side as two triangles over its four corners (bit patterns of the vertex index).
  const int sides[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : sides) addQuad(s, q[0], q[1], q[2], q[3]);
  orientAwayFromOrigin(s);
  return s;
}

TriangleSoup grid(int n, double jitter, unsigned seed) {
  require(n >= 2, "grid needs n >= 2 (got " + std::to_string(n) + ")");
  TriangleSoup s;
  const double h = 1.0 / (n - 1);
  // Raw mt19937 output (fixed by the standard) instead of a std distribution, so the jittered grid
  // is the same natively and in wasm.
  std::mt19937 engine(seed);
  auto symmetric = [&] { return 2.0 * (static_cast<double>(engine()) / 4294967296.0) - 1.0; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      Vec3 p(i * h, j * h, 0.0);
      if (jitter != 0 && i > 0 && j > 0 && i < n - 1 && j < n - 1) {
        p.x() += jitter * h * symmetric();
        p.y() += jitter * h * symmetric();
      }
      s.positions.push_back(p);
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      addQuad(s, a, a + 1, a + n + 1, a + n);  // x then y: counter-clockwise seen from +z
    }
  }
  return s;
}

TriangleSoup icosphere(int level, double radius) {
  require(level >= 0 && level <= 10, "icosphere level must be in [0, 10] (got " +
                                         std::to_string(level) + ")");
  TriangleSoup s;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  // The 12 vertices of an icosahedron: cyclic permutations of (0, ±1, ±φ).
  const double base[12][3] = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& b : base) s.positions.push_back(Vec3(b[0], b[1], b[2]).normalized());
  s.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  orientAwayFromOrigin(s);
  for (int l = 0; l < level; ++l) {
    // Each edge's midpoint is made once and shared by both faces (keyed by its sorted ends), so
    // the result is welded and closed.
    std::unordered_map<std::uint64_t, int> midpoints;
    midpoints.reserve(s.faces.size() * 2);
    auto midpoint = [&](int a, int b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                                static_cast<std::uint32_t>(std::max(a, b));
      auto [it, inserted] = midpoints.try_emplace(key, static_cast<int>(s.positions.size()));
      if (inserted) s.positions.push_back((s.positions[a] + s.positions[b]).normalized());
      return it->second;
    };
    std::vector<Face> faces;
    faces.reserve(s.faces.size() * 4);
    for (const Face& f : s.faces) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({f[1], bc, ab});
      faces.push_back({f[2], ca, bc});
      faces.push_back({ab, bc, ca});
    }
    s.faces = std::move(faces);
  }
  for (Vec3& p : s.positions) p *= radius;
  return s;
}

TriangleSoup cylinder(int sides, int rings, double radius, double height) {
  require(sides >= 3 && rings >= 2, "cylinder needs sides >= 3 and rings >= 2 (got " +
                                        std::to_string(sides) + ", " + std::to_string(rings) + ")");
  TriangleSoup s;
  for (int k = 0; k < rings; ++k) {
    for (int i = 0; i < sides; ++i) {
      const double phi = 2.0 * std::numbers::pi * i / sides;
      s.positions.emplace_back(radius * std::cos(phi), radius * std::sin(phi),
                               height * k / (rings - 1));
    }
  }
  // Around +z then up: tangent × axis is the outward radial direction.
  for (int k = 0; k + 1 < rings; ++k) {
    for (int i = 0; i < sides; ++i) {
      const int i1 = (i + 1) % sides;
      addQuad(s, k * sides + i, k * sides + i1, (k + 1) * sides + i1, (k + 1) * sides + i);
    }
  }
  return s;
}

TriangleSoup torus(int majorSegments, int minorSegments, double R, double r) {
  require(majorSegments >= 3 && minorSegments >= 3, "torus needs at least 3 segments each way");
  TriangleSoup s;
  const int m = minorSegments;
  for (int i = 0; i < majorSegments; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / majorSegments;
    for (int j = 0; j < m; ++j) {
      const double theta = 2.0 * std::numbers::pi * j / m;
      const double ring = R + r * std::cos(theta);
      s.positions.emplace_back(ring * std::cos(phi), ring * std::sin(phi), r * std::sin(theta));
    }
  }
  // ∂p/∂φ × ∂p/∂θ points away from the tube's core circle: φ first, then θ.
  for (int i = 0; i < majorSegments; ++i) {
    const int i1 = (i + 1) % majorSegments;
    for (int j = 0; j < m; ++j) {
      const int j1 = (j + 1) % m;
      addQuad(s, i * m + j, i1 * m + j, i1 * m + j1, i * m + j1);
    }
  }
  return s;
}

TriangleSoup box(int nx, int ny, int nz, const Vec3& size) {
  require(nx >= 1 && ny >= 1 && nz >= 1, "box needs at least one quad per side each way (got " +
                                             std::to_string(nx) + ", " + std::to_string(ny) + ", " +
                                             std::to_string(nz) + ")");
  require(size.allFinite() && size.minCoeff() > 0, "box sides must be positive");
  const std::array<int, 3> n = {nx, ny, nz};
  TriangleSoup s;
  // Surface lattice points keyed by their integer coordinates, so sides share their edge vertices.
  std::unordered_map<std::uint64_t, int> index;
  auto vertex = [&](std::array<int, 3> c) {
    const std::uint64_t key = (static_cast<std::uint64_t>(c[0]) << 42) |
                              (static_cast<std::uint64_t>(c[1]) << 21) | static_cast<std::uint64_t>(c[2]);
    auto [it, inserted] = index.try_emplace(key, static_cast<int>(s.positions.size()));
    if (inserted) {
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = size[k] * (static_cast<double>(c[k]) / n[k] - 0.5);
      s.positions.push_back(p);
    }
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int side : {0, n[axis]}) {
      for (int i = 0; i < n[u]; ++i) {
        for (int j = 0; j < n[w]; ++j) {
          std::array<int, 3> c{};
          c[axis] = side;
          auto at = [&](int di, int dj) {
            c[u] = i + di;
            c[w] = j + dj;
            return vertex(c);
          };
          addQuad(s, at(0, 0), at(1, 0), at(1, 1), at(0, 1));
        }
      }
    }
  }
  orientAwayFromOrigin(s);
  return s;
}

TriangleSoup unwelded(const TriangleSoup& soup) {
  TriangleSoup out;
  out.positions.reserve(soup.faces.size() * 3);
  out.faces.reserve(soup.faces.size());
  for (const Face& f : soup.faces) {
    const int base = static_cast<int>(out.positions.size());
    for (int v : f) out.positions.push_back(soup.positions[v]);
    out.faces.push_back({base, base + 1, base + 2});
  }
  return out;
}

}  // namespace geoshift::shapes

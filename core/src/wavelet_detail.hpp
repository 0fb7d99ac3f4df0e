#pragma once
// Private to the wavelet sources: a half-edge mesh that supports half-edge collapses in place, so
// that one analysis level costs O(removed vertices × valence) instead of a rebuild per collapse.
// Half-edges are implicit in the face corners as in Mesh (h = 3f + k); a collapsed face is marked
// dead and dropped by compact() at the end of the level.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "geoshift/mesh.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift::wavelet_detail {

// The one-ring of a vertex, counter-clockwise. Face i is (v, vertex[i], vertex[i+1 mod size]),
// reached by outgoing[i] (v -> vertex[i]). A boundary vertex has one more vertex than faces:
// v -> vertex[0] and vertex.back() -> v are the boundary edges.
struct Ring {
  std::vector<int> vertex;
  std::vector<int> outgoing;
  bool boundary = false;
  int faces() const { return static_cast<int>(outgoing.size()); }
  int next(int i) const { return boundary ? i + 1 : (i + 1) % static_cast<int>(vertex.size()); }
};

// Positions as the collapse tests read them: rows of a signal matrix whose first three columns are x, y, z.
struct PositionRows {
  const double* data = nullptr;
  int stride = 3;
  Vec3 operator()(int v) const {
    const double* r = data + static_cast<std::size_t>(v) * stride;
    return Vec3(r[0], r[1], r[2]);
  }
};

// Prediction weights of o over its ring (interior) or its two boundary neighbours (boundary), summing
// to 1: the neighbours in `nbr`, the weights in `w`.
void predictionWeights(int o, const Ring& r, const PositionRows& x, WaveletWeights kind, std::vector<int>& nbr,
                       std::vector<double>& w);
// Cosine of the turning angle of the boundary polyline at boundary vertex v.
double turnCosine(int v, const Ring& r, const PositionRows& x);

constexpr int kCostBands = 16;
constexpr std::int64_t kOrderBlock = 4096;
// Upper bounds of cost bands 0 .. kCostBands-2: quantiles of a sample of the costs.
std::vector<double> costBandBounds(const std::vector<double>& cost);
// The vertices (increasing) in ascending cost band (`bounds`), each band in vertex order, block by
// block of kOrderBlock consecutive indices: `wholeIndex[v]` when given (increasing in v), else v.
// Every vertex's place depends on its own cost and index only, so a piece of a mesh given the
// whole's indices and bounds orders its vertices as the whole does.
std::vector<int> bandedOrder(const std::vector<int>& vertices, const std::vector<double>& cost,
                             const std::vector<double>& bounds, const std::int64_t* wholeIndex);

class CollapseMesh {
 public:
  explicit CollapseMesh(const Mesh& mesh);

  int faceCount() const { return static_cast<int>(faces_.size()); }
  const std::vector<Face>& faces() const { return faces_; }
  const std::vector<int>& twins() const { return twin_; }
  bool faceAlive(int f) const { return faces_[f][0] >= 0; }
  bool isolated(int v) const { return vh_[v] < 0; }
  bool boundaryVertex(int v) const { return vh_[v] >= 0 && twin_[vh_[v]] < 0; }

  void ring(int v, Ring& r) const;

  // Whether collapsing o into r.vertex[j] keeps the surface a manifold with the same boundary
  // (link condition, with the boundary treated as a virtual vertex joined to every boundary
  // vertex) and turns no surviving face of o's fan by more than acos(cosMax) or to zero area.
  // A boundary vertex may only collapse along a boundary edge (j = 0 or j = last).
  bool canCollapse(int o, const Ring& r, int j, const PositionRows& x, double cosMax);

  // Applies the collapse checked by canCollapse. Calls keptFace(f, oldCross) for each surviving
  // face of o's fan with its (b - a) × (c - a) before the move.
  template <class KeptFace>
  void collapse(int o, const Ring& r, int j, const PositionRows& x, KeptFace&& keptFace);

  // Level bookkeeping: beginLevel() remembers the state, rollback() returns to it.
  void beginLevel();
  void rollback();
  // Drops dead faces; returns for each new face its index before compaction.
  std::vector<int> compact(const std::vector<int>& liveVertices);

 private:
  int tail(int h) const { return faces_[h / 3][h % 3]; }
  int head(int h) const { return faces_[h / 3][h % 3 == 2 ? 0 : h % 3 + 1]; }
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  void setHalfedge(int v, int h);
  void repairHalfedge(int v, bool boundary, const std::vector<int>& candidates);
  void collapseTopology(int o, const Ring& r, int j);

  std::vector<Face> faces_;
  std::vector<int> twin_;
  std::vector<int> vh_;  // per vertex one outgoing half-edge; the boundary one on the boundary

  std::vector<Face> savedFaces_;
  std::vector<int> savedTwin_;
  std::vector<std::pair<int, int>> vhLog_;  // (vertex, previous half-edge) since beginLevel

  std::vector<std::uint32_t> mark_;
  std::uint32_t markValue_ = 0;
  Ring scratch_;
  std::vector<int> candidates_;
};

template <class KeptFace>
void CollapseMesh::collapse(int o, const Ring& r, int j, const PositionRows& x, KeptFace&& keptFace) {
  const int k = r.faces();
  const int before = r.boundary ? j - 1 : (j + k - 1) % k;  // the other face on edge (o, t)
  const Vec3 xo = x(o);
  for (int i = 0; i < k; ++i) {
    if (i == j || i == before) continue;
    const Vec3 a = x(r.vertex[i]), b = x(r.vertex[r.next(i)]);
    keptFace(r.outgoing[i] / 3, Vec3((a - xo).cross(b - xo)));
  }
  collapseTopology(o, r, j);
}

}  // namespace geoshift::wavelet_detail

// Lifting analysis (docs/algorithms.md#wavelets): per level an independent set of odd vertices, chosen greedily
// in ascending cost, each predicted from its even one-ring and collapsed into one even neighbour;
// then the integral update A'_e = A_e + Σ_o p_oe A_o and the signal update f_e += Σ_o u_eo d_o with
// LOCAAT's minimum-norm u_eo = A_o A'_e / Σ_e' A'_e'^2, which keeps Σ_v A_v f_v exactly invariant.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/wavelet.hpp"
#include "wavelet_detail.hpp"

namespace geoshift {

using wavelet_detail::CollapseMesh;
using wavelet_detail::PositionRows;
using wavelet_detail::Ring;
using wavelet_detail::bandedOrder;
using wavelet_detail::predictionWeights;
using wavelet_detail::turnCosine;

int Multiresolution::channelCount() const {
  int c = 0;
  for (const Attribute& a : layout) c += a.dim;
  return c;
}

std::vector<int> Multiresolution::vertexCounts() const {
  std::vector<int> counts;
  for (const WaveletLevel& l : levels) counts.push_back(l.vertexCount);
  counts.push_back(coarse.vertexCount());
  return counts;
}

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Analyzer {
  const Mesh& mesh;
  const WaveletOptions& opt;
  const Progress& progress;
  int C = 3;
  std::vector<double> F;  // n × C: x, y, z, attribute channels
  std::vector<double> A;  // integrals
  CollapseMesh cm;
  std::vector<int> live;  // vertex ids, increasing
  std::vector<char> status, banned;  // status: 0 free, 1 even (locked), 2 odd
  Ring ring;
  std::vector<int> nbr;
  std::vector<double> w;

  Analyzer(const Mesh& m, const WaveletOptions& o, const Progress& p) : mesh(m), opt(o), progress(p), cm(m) {}

  PositionRows positions() const { return {F.data(), C}; }
  double* row(int v) { return F.data() + static_cast<size_t>(v) * C; }

  // Per level scratch.
  std::vector<char> faceMark, hot;
  std::vector<int> hotList;
  std::vector<Vec3> ref;
  std::vector<int> touched;
  std::vector<double> savedRows, savedA;
  std::vector<char> excluded;

  // One level; false when it removes nothing.
  bool level(int index, WaveletLevel& L, std::vector<int>* parentFace);
  // Predict, integral update, signal update of the selected odd vertices; false when the update of
  // the positions would flip a face and no local restriction of u avoids it.
  bool lift(WaveletLevel& L);
  void applyUpdate(const WaveletLevel& L, int i, double sign);
  void computeUpdate(WaveletLevel& L, int i) const;
  std::vector<int> flippedFaces() const;
  void select(const std::vector<int>& order, WaveletLevel& L, std::vector<char>& faceMark, std::vector<Vec3>& ref);
};

void Analyzer::select(const std::vector<int>& order, WaveletLevel& L, std::vector<char>& faceMark,
                      std::vector<Vec3>& ref) {
  const PositionRows x = positions();
  const double cosMax = std::cos(opt.maxNormalChange * kDegree);
  std::vector<std::pair<double, int>> targets;
  L.odd.clear(), L.target.clear(), L.neighbor.clear(), L.predict.clear();
  L.offset.assign(1, 0);
  for (size_t i = 0; i < order.size(); ++i) {
    if ((i & 0xffff) == 0) progress.step(static_cast<double>(i) / order.size(), "wavelet analysis");
    const int o = order[i];
    if (status[o] != 0 || banned[o]) continue;
    cm.ring(o, ring);
    targets.clear();
    const int n = static_cast<int>(ring.vertex.size());
    for (int j = 0; j < n; ++j) {
      if (ring.boundary && j != 0 && j != n - 1) continue;
      targets.emplace_back((x(ring.vertex[j]) - x(o)).squaredNorm(), j);
    }
    std::sort(targets.begin(), targets.end());
    int chosen = -1;
    for (const auto& [len, j] : targets)
      if (cm.canCollapse(o, ring, j, x, cosMax)) {
        chosen = j;
        break;
      }
    if (chosen < 0) continue;
    predictionWeights(o, ring, x, opt.weights, nbr, w);
    L.odd.push_back(o);
    L.target.push_back(ring.vertex[chosen]);
    L.neighbor.insert(L.neighbor.end(), nbr.begin(), nbr.end());
    L.predict.insert(L.predict.end(), w.begin(), w.end());
    L.offset.push_back(static_cast<int>(L.neighbor.size()));
    status[o] = 2;
    for (int v : ring.vertex) status[v] = 1;
    cm.collapse(o, ring, chosen, x, [&](int f, const Vec3& oldCross) {
      faceMark[f] = 1;
      ref[f] = oldCross;
    });
  }
}

bool Analyzer::level(int index, WaveletLevel& L, std::vector<int>* parentFace) {
  const PositionRows x = positions();
  L.vertexCount = static_cast<int>(live.size());
  // Candidates in ascending cost; boundary vertices only where the polyline is nearly straight.
  const double cosBoundary = opt.boundaryAngle < 0 ? 2.0 : std::cos(opt.boundaryAngle * kDegree);
  std::vector<int> candidates;
  std::vector<double> cost;
  candidates.reserve(live.size());
  cost.reserve(live.size());
  const bool residual = opt.cost == WaveletCost::Residual;
  for (int v : live) {
    if (cm.isolated(v)) continue;
    const bool boundary = cm.boundaryVertex(v);
    if (boundary && opt.boundaryAngle < 0) continue;
    if (boundary || residual) cm.ring(v, ring);
    if (boundary && turnCosine(v, ring, x) < cosBoundary) continue;
    double c = A[v];
    if (residual) {
      predictionWeights(v, ring, x, opt.weights, nbr, w);
      Vec3 p = Vec3::Zero();
      for (size_t i = 0; i < nbr.size(); ++i) p += w[i] * x(nbr[i]);
      c = (x(v) - p).squaredNorm();
    }
    candidates.push_back(v);
    cost.push_back(c);
  }
  const bool given = index < static_cast<int>(opt.costBounds.size()) && !opt.costBounds[index].empty();
  L.costBounds = given ? opt.costBounds[index] : wavelet_detail::costBandBounds(cost);
  const std::vector<int> order =
      bandedOrder(candidates, cost, L.costBounds, opt.wholeIndex.empty() ? nullptr : opt.wholeIndex.data());
  candidates = {};
  cost = {};

  cm.beginLevel();
  for (int v : live) banned[v] = 0;
  for (int attempt = 0;; ++attempt) {
    for (int v : live) status[v] = 0;
    faceMark.assign(cm.faceCount(), 0);
    ref.resize(cm.faceCount());
    select(order, L, faceMark, ref);
    if (L.odd.empty()) return false;
    if (lift(L)) break;
    // The update kept flipping faces: undo the level and keep the odd vertices next to them even.
    for (size_t i = 0; i < touched.size(); ++i) {
      std::copy_n(savedRows.begin() + i * C, C, row(touched[i]));
      A[touched[i]] = savedA[i];
    }
    for (size_t i = 0; i < L.odd.size(); ++i)
      for (int q = L.offset[i]; q < L.offset[i + 1]; ++q)
        if (hot[L.neighbor[q]]) banned[L.odd[i]] = 1;
    for (int v : hotList) hot[v] = 0;
    hotList.clear();
    cm.rollback();
    if (attempt > 64) throw std::logic_error("wavelet: level " + std::to_string(index) + " keeps flipping faces");
  }
  for (int v : hotList) hot[v] = 0;
  hotList.clear();

  std::vector<int> parent = cm.compact(live);
  if (parentFace) *parentFace = std::move(parent);
  std::erase_if(live, [&](int v) { return status[v] == 2; });
  return true;
}

void Analyzer::applyUpdate(const WaveletLevel& L, int i, double sign) {
  const double* d = L.detail.data() + static_cast<size_t>(i) * C;
  for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) {
    const double u = sign * L.update[q];
    if (u == 0) continue;
    double* fe = row(L.neighbor[q]);
    for (int c = 0; c < C; ++c) fe[c] += u * d[c];
  }
}

// LOCAAT's minimum-norm u_eo = A_o A'_e / Σ A'_e'^2 over the neighbours not excluded, so that
// Σ_e A'_e u_eo = A_o (the invariant) holds for any non-empty support.
void Analyzer::computeUpdate(WaveletLevel& L, int i) const {
  double s = 0;
  for (int q = L.offset[i]; q < L.offset[i + 1]; ++q)
    if (!excluded[q]) s += A[L.neighbor[q]] * A[L.neighbor[q]];
  const double Ao = A[L.odd[i]];
  for (int q = L.offset[i]; q < L.offset[i + 1]; ++q)
    L.update[q] = excluded[q] || !(s > 0) ? 0.0 : Ao * A[L.neighbor[q]] / s;
}

std::vector<int> Analyzer::flippedFaces() const {
  const PositionRows x = positions();
  std::vector<int> bad;
  for (int f = 0; f < cm.faceCount(); ++f) {
    if (!faceMark[f] || !cm.faceAlive(f)) continue;
    const Face& t = cm.faces()[f];
    const Vec3 a = x(t[0]), b = x(t[1]), c = x(t[2]);
    const Vec3 n = (b - a).cross(c - a);
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (!(n.norm() > 1e-9 * longest) || !(n.dot(ref[f]) > 0)) bad.push_back(f);
  }
  return bad;
}

bool Analyzer::lift(WaveletLevel& L) {
  const PositionRows x = positions();
  const int m = static_cast<int>(L.odd.size());
  // Every even neighbour moves in the update: remember its row and integral, and the normals of its
  // faces before the move (faces of collapsed fans already hold their normal from before the collapse).
  touched.clear();
  for (int e : L.neighbor)
    if (status[e] == 1) {
      status[e] = 3;
      touched.push_back(e);
    }
  savedRows.resize(touched.size() * C);
  savedA.resize(touched.size());
  for (size_t i = 0; i < touched.size(); ++i) {
    std::copy_n(row(touched[i]), C, savedRows.begin() + i * C);
    savedA[i] = A[touched[i]];
  }
  for (int f = 0; f < cm.faceCount(); ++f) {
    if (faceMark[f] || !cm.faceAlive(f)) continue;
    const Face& t = cm.faces()[f];
    if (status[t[0]] != 3 && status[t[1]] != 3 && status[t[2]] != 3) continue;
    faceMark[f] = 1;
    ref[f] = (x(t[1]) - x(t[0])).cross(x(t[2]) - x(t[0]));
  }
  for (int e : touched) status[e] = 1;

  // Predict from the pre-update evens (batch lifting), then the integral update.
  L.detail.resize(static_cast<size_t>(m) * C);
  for (int i = 0; i < m; ++i) {
    double* d = L.detail.data() + static_cast<size_t>(i) * C;
    std::copy_n(row(L.odd[i]), C, d);
    for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) {
      const double* fe = row(L.neighbor[q]);
      const double p = L.predict[q];
      for (int c = 0; c < C; ++c) d[c] -= p * fe[c];
    }
  }
  for (int i = 0; i < m; ++i)
    for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) A[L.neighbor[q]] += L.predict[q] * A[L.odd[i]];
  L.update.resize(L.neighbor.size());
  excluded.assign(L.neighbor.size(), 0);
  for (int i = 0; i < m; ++i) {
    computeUpdate(L, i);
    applyUpdate(L, i, 1.0);
  }

  // The update moves even vertices. Where that flips or flattens a face, the odd vertices updating
  // its corners send their update to their other neighbours instead (u stays a valid choice).
  for (int round = 0; round < 8; ++round) {
    const std::vector<int> bad = flippedFaces();
    if (bad.empty()) return true;
    for (int f : bad)
      for (int v : cm.faces()[f])
        if (!hot[v]) hot[v] = 1, hotList.push_back(v);
    for (int i = 0; i < m; ++i) {
      bool hit = false;
      for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) hit |= !excluded[q] && hot[L.neighbor[q]];
      if (!hit) continue;
      applyUpdate(L, i, -1.0);
      bool any = false;
      for (int q = L.offset[i]; q < L.offset[i + 1]; ++q) {
        excluded[q] |= hot[L.neighbor[q]];
        any |= !excluded[q];
      }
      if (!any) return false;
      computeUpdate(L, i);
      applyUpdate(L, i, 1.0);
    }
  }
  return flippedFaces().empty();
}

void requireFiniteSignals(const AttributeSet& signals, int n) {
  for (const Attribute& a : signals.all()) {
    if (a.vertexCount() != n || a.values.size() != static_cast<size_t>(n) * a.dim)
      throw InputError("wavelet analysis: attribute '" + a.name + "' has " + std::to_string(a.vertexCount()) +
                       " rows for a mesh of " + std::to_string(n) + " vertices");
    for (size_t i = 0; i < a.values.size(); ++i)
      if (!std::isfinite(a.values[i]))
        throw InputError("wavelet analysis: attribute '" + a.name + "' is not finite at vertex " +
                         std::to_string(i / a.dim));
  }
}

// A mesh from the live vertices (renumbered in increasing id order) and the current faces. The
// collapses kept the twins, so the Mesh skips its edge sort (half the analysis time at L = 1, 2).
WaveletLevelMesh snapshotMesh(const std::vector<int>& live, const CollapseMesh& cm, const std::vector<double>& F,
                              int C, int inputVertices) {
  WaveletLevelMesh s;
  std::vector<int> index(inputVertices, -1);
  std::vector<Vec3> positions(live.size());
  for (size_t i = 0; i < live.size(); ++i) {
    index[live[i]] = static_cast<int>(i);
    const double* r = F.data() + static_cast<size_t>(live[i]) * C;
    positions[i] = Vec3(r[0], r[1], r[2]);
  }
  const std::vector<Face>& faces = cm.faces();
  std::vector<Face> local(faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c) local[f][c] = index[faces[f][c]];
  BuildReport report;
  try {
    s.mesh = Mesh::withTwins(std::move(positions), std::move(local), cm.twins(), &report);
  } catch (const InputError& e) {
    throw std::logic_error(std::string("wavelet: a coarse mesh is not valid: ") + e.what());
  }
  if (!report.clean() || report.splitVertexCopies != 0)
    throw std::logic_error("wavelet: a coarse mesh is not manifold: " +
                           (report.messages.empty() ? std::string("faces dropped") : report.messages.front()));
  s.inputVertex = live;
  return s;
}

// The options and signals analyze() accepts (its contract in wavelet.hpp).
void checkAnalysis(const Mesh& mesh, const AttributeSet& signals, const WaveletOptions& options) {
  requireAtLeast("wavelet analysis: levels", options.levels, 0);
  if (!(options.maxNormalChange > 0 && options.maxNormalChange < 90))
    throw InputError("wavelet analysis: maxNormalChange must be in (0, 90) degrees (got " + formatNumber(options.maxNormalChange) + ")");
  requireFinite("wavelet analysis: boundaryAngle", options.boundaryAngle);
  const int n = mesh.vertexCount();
  if (signals.size() > 0 && signals.vertexCount() != n)
    throw InputError("wavelet analysis: the attributes have " + std::to_string(signals.vertexCount()) +
                     " vertices, the mesh " + std::to_string(n));
  requireFiniteSignals(signals, n);
  if (!options.wholeIndex.empty()) {
    if (options.wholeIndex.size() != static_cast<size_t>(n))
      throw InputError("wavelet analysis: wholeIndex has " + std::to_string(options.wholeIndex.size()) +
                       " entries for the mesh's " + std::to_string(n) + " vertices");
    for (int v = 0; v < n; ++v)
      if (options.wholeIndex[v] < 0 || (v > 0 && options.wholeIndex[v] <= options.wholeIndex[v - 1]))
        throw InputError("wavelet analysis: wholeIndex must be non-negative and increasing; vertex " +
                         std::to_string(v) + " has " + std::to_string(options.wholeIndex[v]));
  }
  for (size_t l = 0; l < options.costBounds.size(); ++l) {
    const std::vector<double>& b = options.costBounds[l];
    if (b.size() >= static_cast<size_t>(wavelet_detail::kCostBands))
      throw InputError("wavelet analysis: costBounds of level " + std::to_string(l) + " has " + std::to_string(b.size()) +
                       " bounds; at most " + std::to_string(wavelet_detail::kCostBands - 1));
    for (size_t k = 0; k < b.size(); ++k)
      if (!std::isfinite(b[k]) || (k > 0 && b[k] < b[k - 1]))
        throw InputError("wavelet analysis: costBounds of level " + std::to_string(l) +
                         " must be finite and ascending (bound " + std::to_string(k) + ")");
  }
}

// The analyzer's start: one row per vertex (position, then every signal's channels in the layout's
// order), the mixed Voronoi areas, every vertex live.
void startAnalyzer(Analyzer& an, const Mesh& mesh, const AttributeSet& signals) {
  const int n = mesh.vertexCount();
  an.F.resize(static_cast<size_t>(n) * an.C);
  for (int v = 0; v < n; ++v) {
    double* r = an.row(v);
    r[0] = mesh.position(v).x(), r[1] = mesh.position(v).y(), r[2] = mesh.position(v).z();
    int c = 3;
    for (const Attribute& a : signals.all()) {
      std::copy_n(a.row(v), a.dim, r + c);
      c += a.dim;
    }
  }
  an.A = mixedVoronoiAreas(mesh);
  an.live.resize(n);
  for (int v = 0; v < n; ++v) an.live[v] = v;
  an.status.assign(n, 0);
  an.banned.assign(n, 0);
  an.hot.assign(n, 0);
}

// The coarse mesh, its integrals and its attributes (unit vectors re-normalised, their norms kept
// for synthesis) from the analyzer's live vertices.
void finishCoarse(Multiresolution& mr, Analyzer& an, const AttributeSet& signals, int n) {
  WaveletLevelMesh coarse = snapshotMesh(an.live, an.cm, an.F, an.C, n);
  mr.coarse = std::move(coarse.mesh);
  mr.coarseToFine = an.live;
  const int nc = static_cast<int>(an.live.size());
  mr.coarseIntegrals.resize(nc);
  for (int i = 0; i < nc; ++i) mr.coarseIntegrals[i] = an.A[an.live[i]];
  mr.coarseAttributes = AttributeSet(nc);
  mr.coarseNorms.resize(mr.layout.size());
  int c0 = 3;
  for (size_t k = 1; k < mr.layout.size(); ++k) {
    const Attribute& a = mr.layout[k];
    std::vector<double> values(static_cast<size_t>(nc) * a.dim);
    for (int i = 0; i < nc; ++i) std::copy_n(an.row(an.live[i]) + c0, a.dim, values.begin() + static_cast<size_t>(i) * a.dim);
    if (a.kind == AttributeKind::UnitVector) {
      std::vector<double>& norms = mr.coarseNorms[k];
      norms.resize(nc);
      for (int i = 0; i < nc; ++i) {
        double* r = values.data() + static_cast<size_t>(i) * a.dim;
        double s = 0;
        for (int d = 0; d < a.dim; ++d) s += r[d] * r[d];
        norms[i] = std::sqrt(s);
        // Opposite normals can cancel; the input row at that vertex is the natural stand-in.
        if (!(norms[i] > 1e-12)) std::copy_n(signals.get(a.name).row(an.live[i]), a.dim, r);
      }
    }
    mr.coarseAttributes.set(a.name, a.dim, a.kind, std::move(values));
    c0 += a.dim;
  }
}

}  // namespace

Multiresolution analyze(const Mesh& mesh, const AttributeSet& signals, const WaveletOptions& options,
                        const Progress& progress) {
  checkAnalysis(mesh, signals, options);
  const int n = mesh.vertexCount();
  Multiresolution mr;
  mr.fine = mesh;
  mr.requestedLevels = options.levels;
  mr.layout.push_back({"position", 3, AttributeKind::Euclidean, {}});
  for (const Attribute& a : signals.all()) mr.layout.push_back({a.name, a.dim, a.kind, {}});

  Analyzer an(mesh, options, progress);
  an.C = mr.channelCount();
  startAnalyzer(an, mesh, signals);
  if (options.keepLevelMeshes) mr.levelMeshes.push_back({mesh, an.live, {}});
  for (int l = 0; l < options.levels; ++l) {
    progress.step(static_cast<double>(l) / options.levels, "wavelet analysis");
    WaveletLevel L;
    std::vector<int> parent;
    if (!an.level(l, L, options.keepLevelMeshes ? &parent : nullptr)) break;
    mr.levels.push_back(std::move(L));
    if (options.keepLevelMeshes) {
      mr.levelMeshes.push_back(snapshotMesh(an.live, an.cm, an.F, an.C, n));
      mr.levelMeshes.back().parentFace = std::move(parent);
    }
  }
  finishCoarse(mr, an, signals, n);
  progress.step(1.0, "wavelet analysis");
  return mr;
}

}  // namespace geoshift

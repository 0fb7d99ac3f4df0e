// 2D Delaunay triangulation by radial sweep (the sweep-hull scheme popularised by delaunator:
// points sorted by distance from a seed circumcentre are added outside a growing convex hull,
// then Lawson flips restore the empty-circle property), on exact integer predicates. A point that
// no hull edge sees — possible only through rounding in the sort, or with InsertionOrder::AsGiven —
// is located by walking and inserted inside.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geoshift/error.hpp"
#include "terrain_detail.hpp"

namespace geoshift::terrain_detail {

namespace {

class Sweep {
 public:
  Sweep(const std::vector<IPoint>& p, int n) : p_(p) {
    const size_t maxTriangles = static_cast<size_t>(std::max(2 * n - 5, 1));
    tri_.reserve(3 * maxTriangles);
    he_.reserve(3 * maxTriangles);
    hullNext_.assign(p.size(), -1);
    hullPrev_.assign(p.size(), -1);
    hullTri_.assign(p.size(), -1);
    hashSize_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(n)))));
    hash_.assign(hashSize_, -1);
  }

  void run(std::vector<int> use, InsertionOrder order, const Progress& progress);
  Triangulation result();

 private:
  bool sees(int p, int a, int b) const { return orient(p_[a], p_[b], p_[p]) < 0; }
  int hashKey(int i) const {
    const double dx = double(p_[i].x) - cx_, dy = double(p_[i].y) - cy_;
    const double s = std::abs(dx) + std::abs(dy);
    if (s == 0) return 0;
    const double q = dx / s;
    const double angle = (dy > 0 ? 3.0 - q : 1.0 + q) / 4.0;  // monotone in the angle, in [0, 1]
    return std::min(hashSize_ - 1, static_cast<int>(angle * hashSize_));
  }
  void link(int a, int b) {
    he_[a] = b;
    if (b >= 0) he_[b] = a;
  }
  int addTriangle(int i0, int i1, int i2, int a, int b, int c) {
    const int t = static_cast<int>(tri_.size());
    tri_.insert(tri_.end(), {i0, i1, i2});
    he_.insert(he_.end(), {-1, -1, -1});
    link(t, a);
    link(t + 1, b);
    link(t + 2, c);
    return t;
  }
  void replaceHullTri(int from, int to) {
    int e = hullStart_;
    do {
      if (hullTri_[e] == from) {
        hullTri_[e] = to;
        return;
      }
      e = hullPrev_[e];  // prev links stay a cycle while the sweep is removing vertices
    } while (e != hullStart_);
  }
  int legalize(int a, bool interiorInsert);
  void addOutside(int i, int e, int start);
  void insertInside(int i);

  const std::vector<IPoint>& p_;
  std::vector<int> tri_, he_, hullNext_, hullPrev_, hullTri_, hash_, stack_;
  int hashSize_ = 1, hullStart_ = -1;
  double cx_ = 0, cy_ = 0;
  std::uint32_t rng_ = 12345u;
};

// Restores the Delaunay property around the new point opposite half-edge a (it sits at the start
// of the previous half-edge of a's triangle); returns that point's outgoing edge of the last
// triangle checked, which the sweep needs for its hull bookkeeping.
int Sweep::legalize(int a, bool interiorInsert) {
  int ar = 0;
  stack_.clear();
  for (;;) {
    const int b = he_[a];
    const int a0 = a - a % 3;
    ar = a0 + (a + 2) % 3;
    if (b < 0) {
      if (stack_.empty()) break;
      a = stack_.back();
      stack_.pop_back();
      continue;
    }
    const int b0 = b - b % 3;
    const int al = a0 + (a + 1) % 3, bl = b0 + (b + 2) % 3;
    const int p0 = tri_[ar], pr = tri_[a], pl = tri_[al], p1 = tri_[bl];
    if (inCircle(p_[p0], p_[pr], p_[pl], p_[p1]) > 0) {
      tri_[a] = p1;
      tri_[b] = p0;
      const int hbl = he_[bl];
      if (hbl < 0) replaceHullTri(bl, a);
      // The sweep keeps its own record of the new point's hull edge; an interior insertion may
      // have put a hull edge at ar, which moves to b.
      if (interiorInsert && he_[ar] < 0) replaceHullTri(ar, b);
      link(a, hbl);
      link(b, he_[ar]);
      link(ar, bl);
      stack_.push_back(b0 + (b + 1) % 3);
    } else {
      if (stack_.empty()) break;
      a = stack_.back();
      stack_.pop_back();
    }
  }
  return ar;
}

void Sweep::addOutside(int i, int e, int start) {
  int t = addTriangle(e, i, hullNext_[e], -1, -1, hullTri_[e]);
  hullTri_[i] = legalize(t + 2, false);
  hullTri_[e] = t;
  int n = hullNext_[e];
  for (int q = hullNext_[n]; sees(i, n, q); q = hullNext_[n]) {
    t = addTriangle(n, i, q, hullTri_[i], -1, hullTri_[n]);
    hullTri_[i] = legalize(t + 2, false);
    hullNext_[n] = n;  // removed from the hull
    n = q;
  }
  if (e == start) {
    for (int q = hullPrev_[e]; sees(i, q, e); q = hullPrev_[e]) {
      t = addTriangle(q, i, e, -1, hullTri_[e], hullTri_[q]);
      legalize(t + 2, false);
      hullTri_[q] = t;
      hullNext_[e] = e;
      e = q;
    }
  }
  hullStart_ = hullPrev_[i] = e;
  hullNext_[e] = hullPrev_[n] = i;
  hullNext_[i] = n;
  hash_[hashKey(i)] = i;
  hash_[hashKey(e)] = e;
}

// i lies inside the hull or on a hull edge: find its triangle by a visibility walk (randomised
// start edge, which cannot cycle) and split it.
void Sweep::insertInside(int i) {
  int t = hullTri_[hullStart_] / 3;
  int onEdge = -1;
  for (;;) {
    rng_ = rng_ * 1664525u + 1013904223u;
    const int k0 = static_cast<int>((rng_ >> 16) % 3);
    int next = -1;
    onEdge = -1;
    for (int j = 0; j < 3 && next < 0; ++j) {
      const int h = 3 * t + (k0 + j) % 3;
      const std::int64_t o = orient(p_[tri_[h]], p_[tri_[h - h % 3 + (h + 1) % 3]], p_[i]);
      if (o < 0) {
        if (he_[h] < 0) throw std::logic_error("Delaunay: point outside the hull seen by no hull edge");
        next = he_[h] / 3;
      } else if (o == 0) {
        onEdge = h;
      }
    }
    if (next < 0) break;
    t = next;
  }
  auto splitTriangle = [&](int h, std::vector<int>& toCheck) {
    // Triangle of h = (a, b, c), h = a->b: becomes (a, b, i), (b, c, i), (c, a, i).
    const int t0 = h - h % 3;
    const int hb = t0 + (h + 1) % 3, hc = t0 + (h + 2) % 3;
    const int a = tri_[h], b = tri_[hb], c = tri_[hc];
    const int twinB = he_[hb], twinC = he_[hc];
    tri_[hc] = i;  // (a, b, i) in the slots h, hb, hc
    const int t1 = addTriangle(b, c, i, twinB, -1, hb);
    const int t2 = addTriangle(c, a, i, twinC, hc, t1 + 1);
    if (twinB < 0) replaceHullTri(hb, t1);
    if (twinC < 0) replaceHullTri(hc, t2);
    (void)a;
    toCheck.insert(toCheck.end(), {h, t1, t2});
  };
  std::vector<int> toCheck;
  if (onEdge < 0) {
    splitTriangle(3 * t, toCheck);
  } else if (he_[onEdge] >= 0) {
    // On an interior edge a->b between (a, b, c) and (b, a, d): four triangles around i.
    const int h = onEdge, g = he_[h];
    const int t0 = h - h % 3, g0 = g - g % 3;
    const int hb = t0 + (h + 1) % 3, hc = t0 + (h + 2) % 3, gb = g0 + (g + 1) % 3, gc = g0 + (g + 2) % 3;
    const int a = tri_[h], c = tri_[hc], b = tri_[g], d = tri_[gc];
    const int twinBc = he_[hb], twinAd = he_[gb];
    // (a, i, c) in h's slots, (i, b, c) new; (b, i, d) in g's slots, (i, a, d) new.
    tri_[hb] = i;
    tri_[gb] = i;
    const int t1 = addTriangle(i, b, c, -1, twinBc, hb);
    const int t2 = addTriangle(i, a, d, -1, twinAd, gb);
    link(h, t2);       // a->i with i->a
    link(g, t1);       // b->i with i->b
    if (twinBc < 0) replaceHullTri(hb, t1 + 1);
    if (twinAd < 0) replaceHullTri(gb, t2 + 1);
    (void)a, (void)b, (void)c, (void)d;
    toCheck.insert(toCheck.end(), {hc, t1 + 1, gc, t2 + 1});
  } else {
    // On the hull edge a->b of (a, b, c): (a, i, c) and (i, b, c); the hull gains i between a and b.
    const int h = onEdge, t0 = h - h % 3;
    const int hb = t0 + (h + 1) % 3, hc = t0 + (h + 2) % 3;
    const int a = tri_[h], b = tri_[hb], c = tri_[hc];
    const int twinBc = he_[hb];
    tri_[hb] = i;
    const int t1 = addTriangle(i, b, c, -1, twinBc, hb);
    if (twinBc < 0) replaceHullTri(hb, t1 + 1);
    hullNext_[a] = i, hullPrev_[i] = a, hullNext_[i] = b, hullPrev_[b] = i;
    hullTri_[a] = h;
    hullTri_[i] = t1;
    hash_[hashKey(i)] = i;
    (void)c;
    toCheck.insert(toCheck.end(), {hc, t1 + 1});
  }
  for (int e : toCheck) legalize(e, true);
}

void Sweep::run(std::vector<int> use, InsertionOrder order, const Progress& progress) {
  const int n = static_cast<int>(use.size());
  if (n < 3) throw InputError("need at least 3 points with distinct xy, got " + std::to_string(n));
  auto dist2 = [&](int i, double x, double y) {
    const double dx = double(p_[i].x) - x, dy = double(p_[i].y) - y;
    return dx * dx + dy * dy;
  };
  auto circumradius2 = [&](int a, int b, int c) {
    const double bx = double(p_[b].x - p_[a].x), by = double(p_[b].y - p_[a].y);
    const double qx = double(p_[c].x - p_[a].x), qy = double(p_[c].y - p_[a].y);
    const double bl = bx * bx + by * by, cl = qx * qx + qy * qy, d = 0.5 / (bx * qy - by * qx);
    const double x = (qy * bl - by * cl) * d, y = (bx * cl - qx * bl) * d;
    return x * x + y * y;
  };
  int i0 = -1, i1 = -1, i2 = -1;
  if (order == InsertionOrder::Sweep) {
    std::int64_t x0 = p_[use[0]].x, x1 = x0, y0 = p_[use[0]].y, y1 = y0;
    for (int i : use) x0 = std::min(x0, p_[i].x), x1 = std::max(x1, p_[i].x), y0 = std::min(y0, p_[i].y), y1 = std::max(y1, p_[i].y);
    const double mx = 0.5 * double(x0 + x1), my = 0.5 * double(y0 + y1);
    double best = std::numeric_limits<double>::infinity();
    for (int i : use)
      if (const double d = dist2(i, mx, my); d < best) best = d, i0 = i;
    best = std::numeric_limits<double>::infinity();
    for (int i : use)
      if (const double d = dist2(i, double(p_[i0].x), double(p_[i0].y)); i != i0 && d < best) best = d, i1 = i;
    best = std::numeric_limits<double>::infinity();
    for (int i : use) {
      if (i == i0 || i == i1 || orient(p_[i0], p_[i1], p_[i]) == 0) continue;
      if (const double r = circumradius2(i0, i1, i); r < best) best = r, i2 = i;
    }
  } else {
    i0 = use[0], i1 = use[1];
    for (int i : use)
      if (orient(p_[i0], p_[i1], p_[i]) != 0) {
        i2 = i;
        break;
      }
  }
  if (i2 < 0) throw InputError("all " + std::to_string(n) + " points are collinear in xy: no triangle");
  if (orient(p_[i0], p_[i1], p_[i2]) < 0) std::swap(i1, i2);

  {  // the hash angles are taken around the seed triangle's circumcentre
    const double ax = double(p_[i0].x), ay = double(p_[i0].y);
    const double bx = double(p_[i1].x) - ax, by = double(p_[i1].y) - ay;
    const double qx = double(p_[i2].x) - ax, qy = double(p_[i2].y) - ay;
    const double bl = bx * bx + by * by, cl = qx * qx + qy * qy, d = 0.5 / (bx * qy - by * qx);
    cx_ = ax + (qy * bl - by * cl) * d;
    cy_ = ay + (bx * cl - qx * bl) * d;
  }
  if (order == InsertionOrder::Sweep) {
    std::vector<std::pair<double, int>> keyed(use.size());
    for (size_t k = 0; k < use.size(); ++k) keyed[k] = {dist2(use[k], cx_, cy_), use[k]};
    std::sort(keyed.begin(), keyed.end());
    for (size_t k = 0; k < use.size(); ++k) use[k] = keyed[k].second;
  }
  hullStart_ = i0;
  hullNext_[i0] = hullPrev_[i2] = i1;
  hullNext_[i1] = hullPrev_[i0] = i2;
  hullNext_[i2] = hullPrev_[i1] = i0;
  hullTri_[i0] = 0, hullTri_[i1] = 1, hullTri_[i2] = 2;
  hash_[hashKey(i0)] = i0, hash_[hashKey(i1)] = i1, hash_[hashKey(i2)] = i2;
  addTriangle(i0, i1, i2, -1, -1, -1);

  for (int k = 0; k < n; ++k) {
    if ((k & 0xffff) == 0) progress.step(double(k) / n, "delaunay");
    const int i = use[k];
    if (i == i0 || i == i1 || i == i2) continue;
    int start = hullStart_;
    const int key = hashKey(i);
    for (int j = 0; j < hashSize_; ++j) {
      const int s = hash_[(key + j) % hashSize_];
      if (s >= 0 && hullNext_[s] != s) {
        start = s;
        break;
      }
    }
    start = hullPrev_[start];
    int e = start;
    while (!sees(i, e, hullNext_[e])) {
      e = hullNext_[e];
      if (e == start) {
        e = -1;
        break;
      }
    }
    if (e < 0) insertInside(i);
    else addOutside(i, e, start);
  }
}

Triangulation Sweep::result() {
  Triangulation t;
  t.corners = std::move(tri_);
  t.halfedges = std::move(he_);
  int e = hullStart_;
  do {
    t.hull.push_back(e);
    e = hullNext_[e];
  } while (e != hullStart_);
  return t;
}

}  // namespace

Triangulation triangulate(const std::vector<IPoint>& points, const std::vector<int>& use,
                          InsertionOrder order, const Progress& progress) {
  // The sweep reads the points in a radial order; a compact copy in Z-order keeps the neighbours
  // it touches together in memory (about a third faster on a million points).
  const int m = static_cast<int>(use.size());
  std::vector<int> global(use);
  if (order == InsertionOrder::Sweep) {
    std::vector<std::pair<std::uint64_t, int>> keyed(m);
    for (int k = 0; k < m; ++k) keyed[k] = {mortonKey(points[use[k]]), use[k]};
    std::sort(keyed.begin(), keyed.end());
    for (int k = 0; k < m; ++k) global[k] = keyed[k].second;
  }
  std::vector<IPoint> local(m);
  for (int k = 0; k < m; ++k) local[k] = points[global[k]];
  std::vector<int> all(m);
  std::iota(all.begin(), all.end(), 0);
  Sweep s(local, m);
  s.run(std::move(all), order, progress);
  Triangulation t = s.result();
  for (int& c : t.corners) c = global[c];
  for (int& h : t.hull) h = global[h];
  return t;
}

}  // namespace geoshift::terrain_detail

namespace geoshift {

Delaunay2D delaunay2d(const std::vector<Vec3>& points, const DelaunayOptions& options,
                      const Progress& progress) {
  using namespace terrain_detail;
  const Snap snap = makeSnap({&points}, "point");
  std::vector<IPoint> ip(points.size());
  for (size_t i = 0; i < points.size(); ++i) ip[i] = snap(points[i]);
  std::vector<int> all(points.size());
  std::iota(all.begin(), all.end(), 0);
  Delaunay2D d;
  d.keptAs = firstOfEqual(ip, all, static_cast<int>(points.size()));
  std::vector<int> use;
  use.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    if (d.keptAs[i] == static_cast<int>(i)) use.push_back(static_cast<int>(i));
  d.duplicates = static_cast<int>(points.size() - use.size());
  Triangulation t = triangulate(ip, use, options.order, progress);
  d.faces.resize(t.triangleCount());
  for (int f = 0; f < t.triangleCount(); ++f) d.faces[f] = {t.corners[3 * f], t.corners[3 * f + 1], t.corners[3 * f + 2]};
  d.twins = std::move(t.halfedges);
  d.hull = std::move(t.hull);
  return d;
}

}  // namespace geoshift

// Where a climb's charts come from (ChartProvider, mean_shift_climb.hpp): log maps at a vertex or
// a group's anchor, binned for the kernel loop, reused from the worker's cache, the kept group
// charts or the store shared by all workers before any is computed again.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mean_shift_climb.hpp"

namespace geoshift::mean_shift_detail {

ChartProvider::ChartProvider(const Setup& setup, LogMap map)
    : logMap(std::move(map)), s_(setup), cache_(cacheSlots(setup)), slot_(setup.mesh.vertexCount(), -1) {}

int ChartProvider::cacheSlots(const Setup& s) {
  // A chart's entries: the vertices within r + r/4 + an edge (a vertex's chart) or the diagonal of
  // an unmerged cube (a group's), at the mean density; each costs about 40 bytes (vertex,
  // coordinates, their single-precision copies, weight and value).
  const double radius = s.r + s.drift + std::max(s.longestEdge, std::sqrt(3.0) * s.cell);
  const double entries = s.vertexArea > 0 ? std::numbers::pi * radius * radius / s.vertexArea : 0;
  const double bytes = 40 * std::max(1.0, entries);
  return static_cast<int>(std::clamp(kCacheBytes / bytes, 4.0, double(kCachedCharts)));
}

ChartView ChartProvider::startChart(int v, const std::vector<double>& signal, const Chart* own) {
  ChartView view;
  if (startsInAnchor(v)) {
    const int slot = slot_[v];
    view.chart = anchor_;
    view.samples = pinned_ ? &pinned_->samples : &anchorSamples_;  // the cached chart's are gathered
    if (fast() && !pinned_ && !anchorGathered_) {  // once per anchor and signal: the group's vertices share it
      gather(anchorSamples_, *anchor_, signal);
      anchorGathered_ = true;
    }
    view.x = anchor_->x[slot];
    view.y = anchor_->y[slot];
    view.reach = anchor_->reach + s_.drift;
  } else if (own) {
    view.chart = own;
    view.samples = &localSamples_;
    if (fast()) gather(localSamples_, *own, signal);
    view.reach = own->reach + s_.drift;
  } else if (!s_.exact) {
    CachedChart& c = cached(v, signal);
    view.chart = &c.chart;
    view.samples = &c.samples;
    view.reach = c.reach;
  } else {
    chartAt(local_, SurfacePoint::atVertex(s_.mesh, v), s_.chartRadius);
    if (fast()) gather(localSamples_, local_, signal);
    view.chart = &local_;
    view.samples = &localSamples_;
    view.reach = s_.drift;
  }
  return view;
}

ChartView ChartProvider::chartFor(const SurfacePoint& p, const std::vector<double>& signal) {
  ChartView view;
  if (s_.exact) {  // the paper's procedure: a fresh log map at the iterate
    chartAt(local_, p, s_.chartRadius);
    if (fast()) gather(localSamples_, local_, signal);
    view.chart = &local_;
    view.samples = &localSamples_;
    return view;
  }
  const int u = s_.mesh.face(p.face)[std::max_element(p.bary.data(), p.bary.data() + 3) - p.bary.data()];
  CachedChart* c = nullptr;
  Vec2 q;
  if (groups_ && s_.cell > 0) {
    const int g = groups_->of[u];
    CachedChart& shared = cached(groups_->anchor[g], signal, g);
    if (locate(shared.chart, s_.mesh, p, q) && q.squaredNorm() <= shared.chart.reach * shared.chart.reach) c = &shared;
  }
  if (!c) {
    c = &cached(u, signal);
    q = inVertexChart(u, p);
  }
  view.chart = &c->chart;
  view.samples = &c->samples;
  view.x = q.x();
  view.y = q.y();
  view.reach = c->reach;
  return view;
}

ChartProvider::CachedChart& ChartProvider::cached(int u, const std::vector<double>& signal, int group) {
  CachedChart* slot = nullptr;
  for (CachedChart& c : cache_) {
    if (c.vertex == u && c.group == group) {
      slot = &c;
      break;
    }
    if (!c.pinned && (!slot || c.used < slot->used)) slot = &c;  // else the least recently used
  }
  if (slot->vertex != u || slot->group != group) {
    slot->vertex = u;
    slot->group = group;
    slot->pass = -1;
    // The same log map when computed before, by any worker.
    const Chart* kept = nullptr;
    if (group >= 0 && groupCharts_ && (*groupReady_)[group].load(std::memory_order_acquire))
      kept = &(*groupCharts_)[group];
    else if (store_)
      kept = store_->find(u, group);
    if (kept) {
      slot->chart = *kept;
    } else {
      if (group >= 0) {  // the group's start chart (u is its anchor)
        chartAt(slot->chart, SurfacePoint::atVertex(s_.mesh, u), s_.r + s_.drift + groups_->reach[group]);
        slot->chart.reach = groups_->reach[group];
      } else {
        vertexChartAt(slot->chart, u);
      }
      if (store_ && store_->worthKeeping(u, group)) store_->keep(u, group, slot->chart);
    }
    slot->reach = slot->chart.reach + s_.drift;
  }
  if (fast() && slot->pass != pass_) {
    gather(slot->samples, slot->chart, signal);
    slot->pass = pass_;
  }
  slot->used = ++clock_;
  return *slot;
}

double ChartProvider::longestEdgeAt(int u) const {
  double longest = 0;
  s_.mesh.forEachOutgoing(u, [&](int h) { longest = std::max(longest, s_.geometry.length(h)); });
  return longest;
}

void ChartProvider::vertexChartAt(Chart& chart, int v) {
  // Wide enough for the kernel around any point of v's faces plus the drift allowance.
  chart.reach = longestEdgeAt(v);
  chartAt(chart, SurfacePoint::atVertex(s_.mesh, v), s_.r + s_.drift + chart.reach);
}

Chart ChartProvider::vertexStartChart(int v) {
  Chart chart;
  if (!s_.mesh.isIsolated(v)) vertexChartAt(chart, v);
  return chart;
}

bool ChartProvider::startsInAnchor(int v) const {
  const int slot = anchor_ ? slot_[v] : -1;
  return slot >= 0 && anchor_->x[slot] * anchor_->x[slot] + anchor_->y[slot] * anchor_->y[slot] <=
                          anchor_->reach * anchor_->reach;
}

bool ChartProvider::locate(const Chart& chart, const Mesh& mesh, const SurfacePoint& p, Vec2& q) {
  const Face& f = mesh.face(p.face);
  int found = 0;
  Vec2 at[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  for (size_t e = 0; e < chart.vertex.size() && found < 3; ++e)
    for (int k = 0; k < 3; ++k)
      if (chart.vertex[e] == f[k]) {
        at[k] = Vec2(chart.x[e], chart.y[e]);
        ++found;
      }
  if (found < 3) return false;
  q = p.bary[0] * at[0] + p.bary[1] * at[1] + p.bary[2] * at[2];
  return true;
}

Vec2 ChartProvider::inVertexChart(int u, const SurfacePoint& p) const {
  const Face& f = s_.mesh.face(p.face);
  const int c = f[0] == u ? 0 : f[1] == u ? 1 : 2;
  const int h = 3 * p.face + c;  // u -> f[c + 1]; the face lies counter-clockwise of it at u
  const double phi = s_.geometry.polarAngle(h);
  const double psi = phi + s_.geometry.angleScale(u) * s_.geometry.cornerAngle(h);
  const double a = p.bary[(c + 1) % 3] * s_.geometry.length(h);
  const double b = p.bary[(c + 2) % 3] * s_.geometry.length(Mesh::prev(h));
  return {a * std::cos(phi) + b * std::cos(psi), a * std::sin(phi) + b * std::sin(psi)};
}

void ChartProvider::chartAt(Chart& chart, const SurfacePoint& base, double radius) {
  ++charts_;
  chart.base = base;
  const std::vector<LogMapEntry>& entries = logMap.compute(base, radius);
  const size_t n = entries.size();
  // A geodesic is no shorter than the straight line, so the chart's boundary vertices' straight
  // distances bound how far a trace goes without meeting them; those beyond the chart are at least
  // its radius away along the surface.
  double nearestBoundary = radius;
  const Vec3 at = base.position(s_.mesh);
  for (const LogMapEntry& e : entries)
    if (s_.mesh.isBoundaryVertex(e.vertex))
      nearestBoundary = std::min(nearestBoundary, (s_.mesh.position(e.vertex) - at).norm());
  chart.clear = nearestBoundary - s_.longestEdge;
  chart.cell = 0.125 * s_.r;
  chart.side = std::max(1, static_cast<int>(std::ceil(2 * radius / chart.cell)) + 1);
  chart.origin = -radius;
  const auto cellOf = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - chart.origin) / chart.cell)), 0, chart.side - 1);
  };
  // Counting sort by cell; within a cell the log map's order (by distance) is kept.
  chart.cellStart.assign(static_cast<size_t>(chart.side) * chart.side + 1, 0);
  order_.resize(n);
  scratchX_.resize(n);
  scratchY_.resize(n);
  for (size_t e = 0; e < n; ++e) {
    scratchX_[e] = entries[e].distance * std::cos(entries[e].angle);
    scratchY_[e] = entries[e].distance * std::sin(entries[e].angle);
    const int c = cellOf(scratchY_[e]) * chart.side + cellOf(scratchX_[e]);
    order_[e] = c;
    ++chart.cellStart[c + 1];
  }
  for (size_t c = 1; c < chart.cellStart.size(); ++c) chart.cellStart[c] += chart.cellStart[c - 1];
  fill_.assign(chart.cellStart.begin(), chart.cellStart.end() - 1);
  chart.vertex.resize(n);
  chart.x.assign(n + kChartPad, 0.0);  // padded for the kernel loop's masked tails
  chart.y.assign(n + kChartPad, 0.0);
  for (size_t e = 0; e < n; ++e) {
    const int at = fill_[order_[e]]++;
    chart.vertex[at] = entries[e].vertex;
    chart.x[at] = scratchX_[e];
    chart.y[at] = scratchY_[e];
  }
}

void ChartProvider::setAnchor(int group, const std::vector<double>& signal) {
  clearAnchor();
  const int vertex = groups_->anchor[group];
  if (s_.mesh.isIsolated(vertex)) return;
  CachedChart& c = cached(vertex, signal, group);
  useAnchor(c.chart);
  c.pinned = true;
  pinned_ = &c;
}

Chart ChartProvider::anchorChart(int vertex, double reach) {
  Chart chart;
  if (!s_.mesh.isIsolated(vertex)) chartAt(chart, SurfacePoint::atVertex(s_.mesh, vertex), s_.r + s_.drift + reach);
  chart.reach = reach;
  return chart;
}

void ChartProvider::useAnchor(const Chart& chart) {
  clearAnchor();
  anchor_ = &chart;
  anchorGathered_ = false;
  for (size_t e = 0; e < chart.vertex.size(); ++e) slot_[chart.vertex[e]] = static_cast<int>(e);
}

void ChartProvider::clearAnchor() {
  if (pinned_) pinned_->pinned = false;
  pinned_ = nullptr;
  if (!anchor_) return;
  for (int v : anchor_->vertex) slot_[v] = -1;
  anchor_ = nullptr;
  anchorGathered_ = false;
}

KeptCharts::KeptCharts(const Groups& groups, bool keep, long long budget)
    : groups_(groups), active_(keep), budget_(budget), group_(keep ? groups.anchor.size() : 0), ready_(group_.size()),
      members_(group_.size()) {}

void KeptCharts::enterGroup(int g, ChartProvider& charts, bool firstPass) {
  if (firstPass) {
    group_[g] = charts.anchorChart(groups_.anchor[g], groups_.reach[g]);
    charts.useAnchor(group_[g]);
    members_[g].resize(groups_.start[g + 1] - groups_.start[g]);
    long long bytes = ChartStore::bytesOf(group_[g]);
    for (int k = groups_.start[g]; k < groups_.start[g + 1]; ++k)
      if (!charts.startsInAnchor(groups_.vertex[k])) {
        members_[g][k - groups_.start[g]] = charts.vertexStartChart(groups_.vertex[k]);
        bytes += ChartStore::bytesOf(members_[g][k - groups_.start[g]]);
      }
    if (bytes_.fetch_add(bytes) + bytes > budget_) full_ = true;
    ready_[g].store(true, std::memory_order_release);
  }
  charts.useAnchor(group_[g]);
}

const Chart* KeptCharts::own(int g, int k) const {
  const Chart& chart = members_[g][k];
  return chart.vertex.empty() ? nullptr : &chart;
}

void KeptCharts::endPass() {
  if (!full_) return;
  active_ = false;
  group_ = {};
  members_ = {};
}

}  // namespace geoshift::mean_shift_detail

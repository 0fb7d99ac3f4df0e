// One vertex's climb to its mode (eq. 6, 7), in a chart that is reused while the iterate stays near
// the chart's centre (the note on speed of the mean shift issue; exact per-iteration charts as an option).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mean_shift_detail.hpp"

namespace geoshift::mean_shift_detail {

Climber::Climber(const Setup& setup, LogMap map)
    : logMap(std::move(map)), vertexCharts_(vertexChartSlots(setup)), s_(setup), slot_(setup.mesh.vertexCount(), -1),
      value_(setup.width), next_(setup.width), acc_(setup.width) {}

int Climber::vertexChartSlots(const Setup& s) {
  // A chart's entries: the vertices within r + r/4 + an edge (a vertex's chart) or the diagonal of
  // an unmerged cube (a group's), at the mean density; each costs about 40 bytes (vertex,
  // coordinates, their single-precision copies, weight and value).
  const double radius = s.r + s.drift + std::max(s.longestEdge, std::sqrt(3.0) * s.cell);
  const double entries = s.vertexArea > 0 ? std::numbers::pi * radius * radius / s.vertexArea : 0;
  const double bytes = 40 * std::max(1.0, entries);
  return static_cast<int>(std::clamp(kVertexChartBytes / bytes, 4.0, double(kVertexCharts)));
}

Climber::VertexChart& Climber::vertexChart(int u, const std::vector<double>& signal, int group) {
  VertexChart* slot = nullptr;
  for (VertexChart& c : vertexCharts_) {
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
  if (s_.loop != Setup::Loop::General && slot->pass != pass_) {
    gather(slot->samples, slot->chart, signal);
    slot->pass = pass_;
  }
  slot->used = ++clock_;
  return *slot;
}

double Climber::longestEdgeAt(int u) const {
  double longest = 0;
  s_.mesh.forEachOutgoing(u, [&](int h) { longest = std::max(longest, s_.geometry.length(h)); });
  return longest;
}

void Climber::vertexChartAt(Chart& chart, int v) {
  // Wide enough for the kernel around any point of v's faces plus the drift allowance.
  chart.reach = longestEdgeAt(v);
  chartAt(chart, SurfacePoint::atVertex(s_.mesh, v), s_.r + s_.drift + chart.reach);
}

Chart Climber::vertexStartChart(int v) {
  Chart chart;
  if (!s_.mesh.isIsolated(v)) vertexChartAt(chart, v);
  return chart;
}

bool Climber::startsInAnchor(int v) const {
  const int slot = anchor_ ? slot_[v] : -1;
  return slot >= 0 && anchor_->x[slot] * anchor_->x[slot] + anchor_->y[slot] * anchor_->y[slot] <=
                          anchor_->reach * anchor_->reach;
}

bool Climber::locate(const Chart& chart, const Mesh& mesh, const SurfacePoint& p, Vec2& q) {
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

Vec2 Climber::inVertexChart(int u, const SurfacePoint& p) const {
  const Face& f = s_.mesh.face(p.face);
  const int c = f[0] == u ? 0 : f[1] == u ? 1 : 2;
  const int h = 3 * p.face + c;  // u -> f[c + 1]; the face lies counter-clockwise of it at u
  const double phi = s_.geometry.polarAngle(h);
  const double psi = phi + s_.geometry.angleScale(u) * s_.geometry.cornerAngle(h);
  const double a = p.bary[(c + 1) % 3] * s_.geometry.length(h);
  const double b = p.bary[(c + 2) % 3] * s_.geometry.length(Mesh::prev(h));
  return {a * std::cos(phi) + b * std::cos(psi), a * std::sin(phi) + b * std::sin(psi)};
}

void Climber::chartAt(Chart& chart, const SurfacePoint& base, double radius) {
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

void Climber::setAnchor(int group, const std::vector<double>& signal) {
  clearAnchor();
  const int vertex = groups_->anchor[group];
  if (s_.mesh.isIsolated(vertex)) return;
  VertexChart& c = vertexChart(vertex, signal, group);
  useAnchor(c.chart);
  c.pinned = true;
  pinned_ = &c;
}

Chart Climber::anchorChart(int vertex, double reach) {
  Chart chart;
  if (!s_.mesh.isIsolated(vertex)) chartAt(chart, SurfacePoint::atVertex(s_.mesh, vertex), s_.r + s_.drift + reach);
  chart.reach = reach;
  return chart;
}

void Climber::useAnchor(const Chart& chart) {
  clearAnchor();
  anchor_ = &chart;
  anchorGathered_ = false;
  for (size_t e = 0; e < chart.vertex.size(); ++e) slot_[chart.vertex[e]] = static_cast<int>(e);
}

void Climber::clearAnchor() {
  if (pinned_) pinned_->pinned = false;
  pinned_ = nullptr;
  if (!anchor_) return;
  for (int v : anchor_->vertex) slot_[v] = -1;
  anchor_ = nullptr;
  anchorGathered_ = false;
}

void Climber::sample(const std::vector<double>& signal, const SurfacePoint& p, double* y) const {
  const Face& f = s_.mesh.face(p.face);
  const double* r[3] = {&signal[f[0] * s_.width], &signal[f[1] * s_.width], &signal[f[2] * s_.width]};
  for (int d = 0; d < s_.width; ++d) y[d] = p.bary[0] * r[0][d] + p.bary[1] * r[1][d] + p.bary[2] * r[2][d];
  for (const Channel& c : s_.channels) {
    if (!c.unit) continue;
    double n2 = 0;
    for (int d = c.offset; d < c.offset + c.dim; ++d) n2 += y[d] * y[d];
    if (n2 > 1e-24) {
      const double k = 1 / std::sqrt(n2);
      for (int d = c.offset; d < c.offset + c.dim; ++d) y[d] *= k;
    } else {  // opposite corners cancel: take the nearest corner's value
      const int k = static_cast<int>(std::max_element(p.bary.data(), p.bary.data() + 3) - p.bary.data());
      std::copy(r[k] + c.offset, r[k] + c.offset + c.dim, y + c.offset);
    }
  }
}

[[gnu::always_inline]] inline double Climber::rangeExponent(const double* y, const double* f) const {
  double a = 0;
  for (const Channel& c : s_.channels) {
    if (c.kernel == RangeKernel::NormalSimilarity) {
      double dot = 0;
      for (int d = c.offset; d < c.offset + c.dim; ++d) dot += y[d] * f[d];
      const double sim = 0.5 + 0.5 * dot;
      if (sim <= 1e-3) return kMaxExponent + 1;
      // eq. 8 divided by its value at equal normals, exp(−1/2h_r²): the same weights after normalisation.
      a += (1 / (sim * sim) - 1) * c.invTwoHr2;
    } else {
      double d2 = 0;
      for (int d = c.offset; d < c.offset + c.dim; ++d) d2 += (y[d] - f[d]) * (y[d] - f[d]);
      a += d2 * c.invTwoHr2;
    }
  }
  return a;
}

double Climber::rangeChange2(const double* a, const double* b) const {
  double total = 0;
  for (const Channel& c : s_.channels) {
    double d2 = 0;
    for (int d = c.offset; d < c.offset + c.dim; ++d) d2 += (a[d] - b[d]) * (a[d] - b[d]);
    total += d2 * 2 * c.invTwoHr2;
  }
  return total;
}

// The entries' signal read through their vertex, any kernel, the Karcher step's log map for unit
// vectors; sums in entry order.
void Climber::generalSums(const Chart& chart, const std::vector<double>& signal, double qx, double qy, double& sw,
                          double& mx, double& my) {
  const int width = s_.width;
  const std::vector<int>& vertex = chart.vertex;
  const std::vector<double>& cx = chart.x;
  const std::vector<double>& cy = chart.y;
  forEachRun(chart, qx, qy, s_.r, [&](int begin, int last) {
    for (int e = begin; e < last; ++e) {
      const double dx = cx[e] - qx, dy = cy[e] - qy, d2 = dx * dx + dy * dy;
      if (d2 > s_.r2) continue;
      const double* f = &signal[static_cast<size_t>(vertex[e]) * width];
      const double a = d2 * s_.invTwoHs2 + rangeExponent(value_.data(), f);
      if (!(a < kMaxExponent)) continue;
      const double w = s_.sampleWeight[vertex[e]] * kernelExp(-a);
      sw += w;
      mx += w * dx;
      my += w * dy;
      if (!s_.joint) continue;
      for (const Channel& c : s_.channels) {
        if (!c.unit) {
          for (int d = c.offset; d < c.offset + c.dim; ++d) acc_[d] += w * f[d];
          continue;
        }
        // log_y(f) on the sphere: the angle between them along the tangent direction to f.
        double dot = 0;
        for (int d = c.offset; d < c.offset + c.dim; ++d) dot += value_[d] * f[d];
        dot = std::clamp(dot, -1.0, 1.0);
        double t2 = 0;
        for (int d = c.offset; d < c.offset + c.dim; ++d) t2 += (f[d] - dot * value_[d]) * (f[d] - dot * value_[d]);
        if (t2 <= 1e-30) continue;
        const double k2 = w * std::acos(dot) / std::sqrt(t2);
        for (int d = c.offset; d < c.offset + c.dim; ++d) acc_[d] += k2 * (f[d] - dot * value_[d]);
      }
    }
  });
}

Climb Climber::run(const std::vector<double>& signal, int v, double* out, const Chart* start) {
  const int width = s_.width;
  const double* own = &signal[static_cast<size_t>(v) * width];
  Climb result;
  if (s_.mesh.isIsolated(v)) {  // no surface around it: nothing to average with
    std::copy(own, own + width, out);
    return result;
  }
  SurfacePoint p = SurfacePoint::atVertex(s_.mesh, v);
  const Chart* chart = &local_;
  const Samples* samples = &localSamples_;
  const bool fast = s_.loop != Setup::Loop::General;
  double qx = 0, qy = 0;  // the iterate in `chart`
  double reach = s_.drift;  // how far from the chart's centre the iterate may go before a new chart
  if (startsInAnchor(v)) {
    const int slot = slot_[v];
    chart = anchor_;
    samples = pinned_ ? &pinned_->samples : &anchorSamples_;  // the cached chart's are gathered
    if (fast && !pinned_ && !anchorGathered_) {  // once per anchor and signal: the group's vertices share it
      gather(anchorSamples_, *anchor_, signal);
      anchorGathered_ = true;
    }
    qx = anchor_->x[slot];
    qy = anchor_->y[slot];
    reach = anchor_->reach + s_.drift;
  } else if (start) {
    chart = start;
    if (fast) gather(localSamples_, *start, signal);
    reach = start->reach + s_.drift;
  } else if (!s_.exact) {
    VertexChart& c = vertexChart(v, signal);
    chart = &c.chart;
    samples = &c.samples;
    reach = c.reach;
  } else {
    chartAt(local_, p, s_.chartRadius);
    if (fast) gather(localSamples_, local_, signal);
  }
  std::copy(own, own + width, value_.begin());
  result.converged = false;
  // Joint steps read the iterate's surface point only to change charts and at the end; sampled ones
  // read the signal there after every step.
  const bool defer = s_.joint && !s_.exact;
  bool pending = false;  // p lags (qx, qy) in `chart`
  const auto settle = [&] {
    if (!pending) return;
    p = expMap(s_.geometry, chart->base, Vec2(qx, qy)).end;
    pending = false;
  };
  for (int k = 0; k < s_.kmax; ++k) {
    double sw = 0, mx = 0, my = 0;
    if (s_.joint) std::fill(acc_.begin(), acc_.end(), 0.0);
    if (fast)
      kernelSums(*chart, *samples, qx, qy, sw, mx, my);
    else
      generalSums(*chart, signal, qx, qy, sw, mx, my);
    if (!(sw > 0)) {  // nothing within reach (all weights underflow): the iterate stays
      result.converged = true;
      break;
    }
    mx /= sw;
    my /= sw;
    const double step = std::sqrt(mx * mx + my * my);
    bool rebase = s_.exact, stuck = false;
    if (step > 1e-3 * s_.eps) {  // a shorter step would not move the point measurably
      const double tx = qx + mx, ty = qy + my;
      if (defer && chart->clear > 0 && tx * tx + ty * ty < chart->clear * chart->clear) {
        // No boundary within reach of the trace: it would end where the chart says, so it waits
        // until p is read (the trace of the final (qx, qy) is the one every step would have made).
        qx = tx;
        qy = ty;
        pending = true;
      } else {
        settle();
        const ExpMapResult trace = expMap(s_.geometry, chart->base, Vec2(tx, ty));
        if (trace.hitBoundary) {
          // Clipped at the boundary: the chart's coordinates no longer say where the iterate is.
          stuck = (trace.end.position(s_.mesh) - p.position(s_.mesh)).norm() < 0.5 * s_.eps;
          rebase = true;
        } else {
          qx = tx;
          qy = ty;
        }
        p = trace.end;
      }
    }
    if (s_.joint) {
      for (const Channel& c : s_.channels) {
        if (!c.unit) {
          for (int d = c.offset; d < c.offset + c.dim; ++d) next_[d] = acc_[d] / sw;
          continue;
        }
        // One Karcher step: y ← exp_y(mean of log_y(f_j)).
        double len2 = 0;
        for (int d = c.offset; d < c.offset + c.dim; ++d) len2 += (acc_[d] / sw) * (acc_[d] / sw);
        const double len = std::sqrt(len2);
        double n2 = 0;
        for (int d = c.offset; d < c.offset + c.dim; ++d) {
          next_[d] = len > 1e-30 ? std::cos(len) * value_[d] + std::sin(len) * (acc_[d] / sw) / len : value_[d];
          n2 += next_[d] * next_[d];
        }
        for (int d = c.offset; d < c.offset + c.dim; ++d) next_[d] /= std::sqrt(n2);
      }
    } else {
      sample(signal, p, next_.data());
    }
    const double change = rangeChange2(value_.data(), next_.data());
    value_.swap(next_);
    ++result.iterations;
    if (stuck || (step <= s_.eps && (!s_.joint || change <= s_.rangeTolerance2))) {
      result.converged = true;
      break;
    }
    if (s_.exact) {  // the paper's procedure: a fresh log map at the iterate
      chartAt(local_, p, s_.chartRadius);
      if (fast) gather(localSamples_, local_, signal);
      chart = &local_;
      samples = &localSamples_;
      qx = qy = 0;
    } else if (rebase || qx * qx + qy * qy > reach * reach) {
      settle();
      const int u = s_.mesh.face(p.face)[std::max_element(p.bary.data(), p.bary.data() + 3) - p.bary.data()];
      // The start chart of u's group serves when p is within its reach: the climbs that cross a
      // region share its chart. Else the chart at u.
      VertexChart* c = nullptr;
      Vec2 q;
      if (groups_ && s_.cell > 0) {
        const int g = groups_->of[u];
        VertexChart& shared = vertexChart(groups_->anchor[g], signal, g);
        if (locate(shared.chart, s_.mesh, p, q) && q.squaredNorm() <= shared.chart.reach * shared.chart.reach)
          c = &shared;
      }
      if (!c) {
        c = &vertexChart(u, signal);
        q = inVertexChart(u, p);
      }
      chart = &c->chart;
      samples = &c->samples;
      qx = q.x();
      qy = q.y();
      reach = c->reach;
    }
  }
  settle();
  std::copy(value_.begin(), value_.end(), out);
  result.mode = p;
  return result;
}

}  // namespace geoshift::mean_shift_detail

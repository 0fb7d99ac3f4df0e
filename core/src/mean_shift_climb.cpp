// One vertex's climb to its mode: the paper's eq. 6-7 iteration over the charts a ChartProvider
// supplies (mean_shift_charts.cpp; docs/algorithms.md#mean-shift, #charts).
#include <algorithm>
#include <cmath>

#include "mean_shift_climb.hpp"

namespace geoshift::mean_shift_detail {

Climber::Climber(const Setup& setup, LogMap map)
    : charts(setup, std::move(map)), s_(setup), value_(setup.width), next_(setup.width), acc_(setup.width) {}

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

void Climber::sums(const ChartView& view, const std::vector<double>& signal, double& sw, double& mx, double& my) {
  if (s_.joint) std::fill(acc_.begin(), acc_.end(), 0.0);
  if (s_.loop != Setup::Loop::General)
    kernelSums(*view.chart, *view.samples, view.x, view.y, sw, mx, my);
  else
    generalSums(*view.chart, signal, view.x, view.y, sw, mx, my);
}

void Climber::rangeStep(const std::vector<double>& signal, const SurfacePoint& p, double sw) {
  if (!s_.joint) {
    sample(signal, p, next_.data());
    return;
  }
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
}

Climb Climber::run(const std::vector<double>& signal, int v, double* out, const Chart* own) {
  const int width = s_.width;
  const double* start = &signal[static_cast<size_t>(v) * width];
  Climb result;
  if (s_.mesh.isIsolated(v)) {  // no surface around it: nothing to average with
    std::copy(start, start + width, out);
    return result;
  }
  SurfacePoint p = SurfacePoint::atVertex(s_.mesh, v);
  ChartView view = charts.startChart(v, signal, own);
  std::copy(start, start + width, value_.begin());
  result.converged = false;
  // Joint steps read the iterate's surface point only to change charts and at the end; sampled ones
  // read the signal there after every step.
  const bool defer = s_.joint && !s_.exact;
  bool pending = false;  // p lags (view.x, view.y)
  const auto settle = [&] {
    if (!pending) return;
    p = expMap(s_.geometry, view.chart->base, Vec2(view.x, view.y)).end;
    pending = false;
  };
  for (int k = 0; k < s_.kmax; ++k) {
    // Eq. 6: the weighted mean m of the log map of the samples around the iterate.
    double sw = 0, mx = 0, my = 0;
    sums(view, signal, sw, mx, my);
    if (!(sw > 0)) {  // nothing within reach (all weights underflow): the iterate stays
      result.converged = true;
      break;
    }
    mx /= sw;
    my /= sw;
    // Eq. 7: p ← exp_p(m), traced in the chart from its base.
    const double step = std::sqrt(mx * mx + my * my);
    bool rebase = s_.exact, stuck = false;
    if (step > 1e-3 * s_.eps) {  // a shorter step would not move the point measurably
      const double tx = view.x + mx, ty = view.y + my;
      const double clear = view.chart->clear;
      if (defer && clear > 0 && tx * tx + ty * ty < clear * clear) {
        // No boundary within reach of the trace: it would end where the chart says, so it waits
        // until p is read (the trace of the final (x, y) is the one every step would have made).
        view.x = tx;
        view.y = ty;
        pending = true;
      } else {
        settle();
        const ExpMapResult trace = expMap(s_.geometry, view.chart->base, Vec2(tx, ty));
        if (trace.hitBoundary) {
          // Clipped at the boundary: the chart's coordinates no longer say where the iterate is.
          stuck = (trace.end.position(s_.mesh) - p.position(s_.mesh)).norm() < 0.5 * s_.eps;
          rebase = true;
        } else {
          view.x = tx;
          view.y = ty;
        }
        p = trace.end;
      }
    }
    rangeStep(signal, p, sw);
    const double change = rangeChange2(value_.data(), next_.data());
    value_.swap(next_);
    ++result.iterations;
    if (stuck || (step <= s_.eps && (!s_.joint || change <= s_.rangeTolerance2))) {
      result.converged = true;
      break;
    }
    if (rebase || view.x * view.x + view.y * view.y > view.reach * view.reach) {
      settle();
      view = charts.chartFor(p, signal);
    }
  }
  settle();
  std::copy(value_.begin(), value_.end(), out);
  result.mode = p;
  return result;
}

}  // namespace geoshift::mean_shift_detail

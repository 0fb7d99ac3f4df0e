#pragma once
// Progress reporting and cancellation for long calls.
#include <atomic>
#include <functional>
#include <string_view>

#include "geoshift/error.hpp"

namespace geoshift {

struct Progress {
  // Called with the fraction done in [0, 1] of the named stage. May be empty.
  std::function<void(double fraction, std::string_view stage)> report;
  // Raised by another thread to ask the call to stop; it then throws Cancelled. May be null.
  const std::atomic<bool>* cancel = nullptr;

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
  // Reports and throws Cancelled when the flag is raised.
  void step(double fraction, std::string_view stage) const {
    if (cancelled()) throw Cancelled();
    if (report) report(fraction, stage);
  }
  // The progress of a sub-step that is the fraction [from, to] of this one (same cancel flag).
  // Refers to this Progress, which must outlive it.
  Progress slice(double from, double to) const {
    Progress p;
    p.cancel = cancel;
    if (report)
      p.report = [this, from, to](double f, std::string_view stage) { report(from + (to - from) * f, stage); };
    return p;
  }
};

}  // namespace geoshift

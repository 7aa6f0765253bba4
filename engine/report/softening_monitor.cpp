#include "engine/report/softening_monitor.hpp"

#include <cmath>

namespace rockdd {

bool SofteningMonitor::observe(long at_step, double at_time, double v, double drop) {
  step = at_step;
  time = at_time;
  value = v;
  if (std::abs(v) > peak) {
    peak = std::abs(v);
    peak_step = at_step;
    peak_time = at_time;
  }
  reached = peak > 0.0 && std::abs(v) <= (1.0 - drop) * peak;
  return reached;
}

}  // namespace rockdd

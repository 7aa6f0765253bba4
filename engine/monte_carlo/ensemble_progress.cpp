#include "engine/monte_carlo/ensemble_progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockdd {

std::string clock_time(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  std::snprintf(text, sizeof text, "%02ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

std::string progress_line(const EnsembleProgress& p) {
  std::string line = "mc: " + std::to_string(p.done) + "/" + std::to_string(p.total) + " done, " +
                     std::to_string(p.running) + " running, " + std::to_string(p.failed) +
                     " failed, ";
  if (p.finished_here == 0 || p.elapsed_s <= 0.0) return line + "-- realizations/h, ETA --";
  const double per_second = static_cast<double>(p.finished_here) / p.elapsed_s;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.0f", per_second * 3600.0);
  return line + rate + " realizations/h, ETA " +
         clock_time(static_cast<double>(p.total - p.done) / per_second);
}

}  // namespace rockdd

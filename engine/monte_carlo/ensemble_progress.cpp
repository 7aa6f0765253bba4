#include "engine/monte_carlo/ensemble_progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <queue>

namespace rockdd {

std::string clock_time(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  std::snprintf(text, sizeof text, "%02ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

double ensemble_eta_seconds(const EnsembleProgress& p) {
  if (p.done >= p.total) return 0.0;
  if (p.finished_here == 0 || p.mean_realization_s <= 0.0) return -1.0;
  const double mean = p.mean_realization_s;
  // Each slot's time until it frees: a running realization's expected rest, or 0 when idle.
  std::priority_queue<double, std::vector<double>, std::greater<>> free_at;
  for (const double ran : p.running_for) free_at.push(std::max(0.0, mean - ran));
  // Running realizations whose start is unknown here (MPI peers): half a realization left.
  for (long i = static_cast<long>(p.running_for.size()); i < p.running; ++i) free_at.push(0.5 * mean);
  const long slots = std::max(p.slots, p.running);
  while (static_cast<long>(free_at.size()) < std::max(1L, slots)) free_at.push(0.0);
  const long waiting = std::max(0L, p.total - p.done - p.running);
  for (long i = 0; i < waiting; ++i) {
    const double start = free_at.top();
    free_at.pop();
    free_at.push(start + mean);
  }
  double end = 0.0;
  while (!free_at.empty()) {
    end = std::max(end, free_at.top());
    free_at.pop();
  }
  return end;
}

std::string progress_line(const EnsembleProgress& p) {
  std::string line = "mc: " + std::to_string(p.done) + "/" + std::to_string(p.total) + " done, " +
                     std::to_string(p.running) + " running, " + std::to_string(p.failed) +
                     " failed, ";
  const double eta = ensemble_eta_seconds(p);
  if (p.finished_here == 0 || p.elapsed_s <= 0.0)
    return line + "-- realizations/h, ETA " + (eta >= 0.0 ? clock_time(eta) : "--");
  const double per_second = static_cast<double>(p.finished_here) / p.elapsed_s;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.0f", per_second * 3600.0);
  return line + rate + " realizations/h, ETA " + (eta >= 0.0 ? clock_time(eta) : "--");
}

}  // namespace rockdd

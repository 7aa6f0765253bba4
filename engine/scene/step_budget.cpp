#include "engine/scene/step_budget.hpp"

#include <algorithm>
#include <cmath>

namespace rockdd {

double scene_steps(const TimeSpec& time) {
  if (time.steps) return *time.steps;
  if (!time.end || !(time.dt > 0)) return 1.0;
  const double end = *time.end;
  double whole = std::floor(end / time.dt);
  // What is left after the whole steps: a step of its own unless it is shorter than dt_min
  // (merged into the last whole step) or within the loop's 1e-12 of the end.
  const double rest = end - whole * time.dt;
  if (rest > std::max(time.dt_min, end * 1e-12)) whole += 1.0;
  return std::max(whole, 1.0);
}

RunTimeEstimate estimated_run_time(double steps, std::size_t elements) {
  const double work = steps * static_cast<double>(std::max<std::size_t>(elements, 1));
  return {work * kFastestStepSecondsPerElement, work * kSlowestStepSecondsPerElement};
}

}  // namespace rockdd

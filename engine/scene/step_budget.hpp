#pragma once
// How long a run is, known from its scene: its steps, the budget they must fit (a static
// scene with time.dt = 1e-300 and time.end = 1 passed `rockdd check` and asked its run for
// 1e300 steps, issue 28), and the time they take.
#include <cstddef>
#include <cstdint>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// The steps a run of `time` takes at time.dt, whatever dt control does later: time.steps,
/// or time.end / time.dt rounded up, where a last step shorter than time.dt_min is merged
/// into the one before (StepControl::step_to) and a remainder within 1e-12 of time.end is
/// not a step (the step loop's end). At least 1.
double scene_steps(const TimeSpec& time);

/// The fastest and the slowest cost of a step per element, s, measured on data/'s scenes on
/// 2 threads of the development machine (wall time over steps x elements): 0.69 us for the
/// sliding block (306 elements, 1,500 dynamic steps with contact) and the displacement-
/// controlled disk (3,092, 223 quasi-static steps), 8.3 us for the cracking disk (3,092, 6
/// steps full of damage passes); the 8,100-element compression specimen took 5.0 us.
constexpr double kFastestStepSecondsPerElement = 0.69e-6;
constexpr double kSlowestStepSecondsPerElement = 8.3e-6;

/// The range of the run time of `steps` steps of a mesh of `elements`, s: what `rockdd check`
/// prints. A rough one: damage, contact and dt control move a run within it and beyond.
struct RunTimeEstimate {
  double fastest = 0.0, slowest = 0.0;
};
RunTimeEstimate estimated_run_time(double steps, std::size_t elements);

}  // namespace rockdd

#include "engine/time/step_control.hpp"

#include <algorithm>
#include <cstdio>

#include "engine/common/errors.hpp"

namespace rockdd {

StepControl::StepControl(const TimeSpec& time)
    : dt_(time.dt),
      dt_first_(time.dt),
      dt_min_(time.dt_min > 0 ? time.dt_min : time.dt * 1e-6),
      dt_max_(time.dt_max > 0 ? time.dt_max : time.dt),
      max_displacement_(time.max_step_displacement) {}

void StepControl::reject(long step, const std::string& why) {
  dt_ *= 0.5;
  ++changes_;
  easy_in_a_row_ = 0;
  if (dt_ < dt_min_) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " (dt %.3g s would fall below dt_min %.3g s)", dt_, dt_min_);
    throw RunFailure("step " + std::to_string(step) + ": " + why + buf);
  }
}

void StepControl::accept(bool easy, bool quiet) {
  easy_in_a_row_ = easy ? easy_in_a_row_ + 1 : 0;
  const double largest = quiet ? dt_max_ : std::min(dt_max_, dt_first_);
  if (easy_in_a_row_ >= 10 && dt_ < largest) {
    dt_ = std::min(dt_ * 1.5, largest);
    ++changes_;
    easy_in_a_row_ = 0;
  }
}

void StepControl::restart_growth() {
  easy_in_a_row_ = 0;
  if (dt_ <= dt_first_) return;
  dt_ = dt_first_;
  ++changes_;
}

void StepControl::restart_at(double dt) {
  dt_ = dt;
  dt_max_ = dt;
  dt_min_ = dt * 1e-6;
  easy_in_a_row_ = 0;
  ++changes_;
}

bool StepControl::displacement_ok(double max_increment) const {
  return !max_displacement_ || max_increment <= *max_displacement_;
}

}  // namespace rockdd

#include "engine/time/onset_cuts.hpp"

namespace rockdd {

double OnsetCuts::next(double dt, double fraction, double largest, bool settled) {
  ++cuts_;
  double length = fraction * dt;
  if (!settled) return length;
  if (settled_ && settled_->first > dt && settled_->second > largest) {
    const double slope = (settled_->second - largest) / (settled_->first - dt);
    const double at_no_length = largest - slope * dt;
    if (at_no_length >= target_) {
      // The onset is the settling's: a step of no length settles and runs it at the load it
      // has (as the step after a located onset does).
      constexpr double kLastCut = 0.1;
      cuts_ = kMostCuts;
      length = may_stand_ ? 0.0 : kLastCut * dt;
    } else {
      length = dt - (largest - target_) / slope;
    }
  }
  settled_.emplace(dt, largest);
  return length;
}

}  // namespace rockdd

#include "engine/time/onset_cuts.hpp"

namespace rockdd {

double OnsetCuts::next(double dt, double fraction, double largest, bool settled) {
  ++cuts_;
  // The first solve and the settled growth bend the path differently: each has its own line.
  std::optional<std::pair<double, double>>& last = settled ? settled_ : first_solve_;
  double length = fraction * dt;
  if (last && last->first > dt && last->second > largest) {
    const double slope = (last->second - largest) / (last->first - dt);
    const double at_no_length = largest - slope * dt;
    if (settled) {
      if (at_no_length >= target_) {
        // The onset is the settling's: a step of no length settles and runs it at the load it
        // has (as the step after a located onset does).
        constexpr double kLastCut = 0.1;
        cuts_ = kMostCuts;
        length = may_stand_ ? 0.0 : kLastCut * dt;
      } else {
        length = dt - (largest - target_) / slope;
      }
    } else if (at_no_length >= target_ && may_stand_) {
      // The first solve's settling of the imbalance the step starts with passes the onset,
      // whatever the step's length: shorter cuts would only creep towards no length. The step
      // has none, and settles its growth before it seeks the onsets, as a step with length does.
      cuts_ = kMostCuts;
      length = 0.0;
      locates_at_no_length_ = true;
    }
  }
  last.emplace(dt, largest);
  return length;
}

}  // namespace rockdd

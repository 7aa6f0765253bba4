#pragma once
// Step-size control: a step that fails a check is redone with half the step; dt grows
// back by 1.5x after a run of easy steps, never above dt_max; below dt_min the run fails.
#include <optional>
#include <string>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// The current dt and how it changes.
class StepControl {
 public:
  explicit StepControl(const TimeSpec& time);
  double dt() const { return dt_; }
  /// The next step's length with `remaining` s left to the end: dt, or all that is left when
  /// it is less, or when a step of dt would leave less than dt_min, which would make a last
  /// step shorter than dt_min (end = 1, dt = 1e-5 once took a last step of 1.9e-12 s): that
  /// remainder is merged into this step, at most dt_min longer than dt.
  double step_to(double remaining) const { return remaining - dt_ < dt_min_ ? remaining : dt_; }
  /// Halves dt after a failed attempt; throws RunFailure (with `why`) when dt < dt_min.
  void reject(long step, const std::string& why);
  /// Records a committed step; grows dt by 1.5x after 10 easy steps in a row: up to dt_max
  /// when the last step was also `quiet`, otherwise back up to the first dt at most.
  void accept(bool easy, bool quiet);
  /// After a located onset: dt no larger than the scene's first dt, and growth starts over.
  void restart_growth();
  /// Goes on at `dt` (also the new largest; the smallest 1e-6 of it): a run that changes its
  /// kind of analysis (fracture.snap_back = "dynamic").
  void restart_at(double dt);
  /// True when a step's largest displacement increment is acceptable.
  bool displacement_ok(double max_increment) const;
  long changes() const { return changes_; }

 private:
  double dt_, dt_first_, dt_min_, dt_max_;
  std::optional<double> max_displacement_;
  int easy_in_a_row_ = 0;
  long changes_ = 0;
};

}  // namespace rockdd

#pragma once
// The cuts of one step back to an undamaged element's onset (docs/method-choices.md,
// "Located onsets"): how long the next attempt of the step is.
#include <optional>
#include <utility>

namespace rockdd {

/// Chooses each next length of a step that passed an onset, until one ends within the
/// tolerance of it or the cuts run out.
class OnsetCuts {
 public:
  /// `target`: the onset ratio a located onset is cut back to (1 + half its tolerance).
  /// Without `may_stand`, a step may not be given no length (the last one had none and
  /// started no damage: another would change nothing).
  OnsetCuts(double target, bool may_stand) : target_(target), may_stand_(may_stand) {}

  /// Whether the step may still be cut.
  bool may_cut() const { return cuts_ < kMostCuts; }

  /// The next length of an attempt of length `dt` that passed an onset: `fraction` of it, where
  /// the elements' straight paths reach the target; once two attempts measured their `largest`
  /// ratio after their damage growth settled (`settled`), the root of the line through those
  /// two (the growth bends the path, which the straight paths miss). When that line stays
  /// above the target at no length, the settling alone passes the onset, not the load: the
  /// step has no length, and its damage passes settle and run the onset at the load it has
  /// (or, where it may not stand, a last tenth of it, not cut again). Two attempts cut at
  /// their first solve draw the same line: where it stays above the target at no length, the
  /// first solve's settling of the imbalance the step started with (the last step's final
  /// growth, a detachment's split nodes) passes the onset, and the step has no length but
  /// locates the onset as a step with length does (locates_at_no_length).
  double next(double dt, double fraction, double largest, bool settled);

  /// Whether the step, given no length because its first solve's settling passes an onset,
  /// settles its damage growth and then locates that onset (the next step runs it), as a step
  /// with length does; otherwise a step of no length starts its onsets with its first pass.
  bool locates_at_no_length() const { return locates_at_no_length_; }

 private:
  static constexpr int kMostCuts = 8;

  double target_;
  bool may_stand_;
  int cuts_ = 0;
  bool locates_at_no_length_ = false;
  // (length, largest ratio) of the last attempt cut after its first solve, and after its
  // growth settled.
  std::optional<std::pair<double, double>> first_solve_, settled_;
};

}  // namespace rockdd

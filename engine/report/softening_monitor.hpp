#pragma once
// The end on softening (time.stop_at_softening): the peak of one history column and whether
// it has fallen the scene's fraction below it. summary.json's "softening".
namespace rockdd {

/// The watched column's peak magnitude, where it was, and its last value.
struct SofteningMonitor {
  double peak = 0.0, peak_time = 0.0;
  long peak_step = 0;
  bool reached = false;
  long step = 0;
  double time = 0.0, value = 0.0;

  /// Takes the value `v` of a committed step; true once |v| has fallen `drop` (a fraction)
  /// below the largest magnitude seen so far.
  bool observe(long at_step, double at_time, double v, double drop);
};

}  // namespace rockdd

#pragma once
// Wall-clock timers of the set-up and of the step stages, reported in summary.json under
// "timers". A stage's time is its own: a timer started inside another pauses the outer one,
// so the stages add up to the run's wall time without counting any second twice.
#include <chrono>

namespace rockdd {

/// Seconds spent in each stage of the step loop.
struct StageTimers {
  double assembly = 0, factorization = 0, solve = 0, contact = 0, damage = 0, output = 0;
  double layout = 0;    // sparsity pattern and scatter map, when contacts or blocks change
  double analysis = 0;  // CHOLMOD's symbolic analysis (ordering, supernodes) of a new pattern
  double detachment = 0;  // damaged elements made fragments, and the stages rebuilt on them
  double sum() const {
    return assembly + factorization + solve + contact + damage + detachment + output + layout +
           analysis;
  }
};

/// Seconds spent building a Simulation, before its first step.
struct SetupTimers {
  double layout = 0;    // the first sparsity pattern, scatter map and element colouring
  double analysis = 0;  // CHOLMOD's symbolic analysis of it
  double other = 0;     // boundary conditions, loads, probes, contact and damage stages
  double sum() const { return layout + analysis + other; }
};

/// Adds the lifetime of the scope, less that of timers nested in it, to one accumulator.
/// Timers nest per thread; the engine starts them only on the thread that runs the steps.
class ScopedTimer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit ScopedTimer(double& seconds) : seconds_(seconds), outer_(active_), start_(Clock::now()) {
    if (outer_) outer_->pause(start_);
    active_ = this;
  }
  ~ScopedTimer() {
    const Clock::time_point now = Clock::now();
    pause(now);
    active_ = outer_;
    if (outer_) outer_->start_ = now;
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  void pause(Clock::time_point now) {
    seconds_ += std::chrono::duration<double>(now - start_).count();
  }
  double& seconds_;
  ScopedTimer* outer_;
  Clock::time_point start_;
  static inline thread_local ScopedTimer* active_ = nullptr;
};

}  // namespace rockdd

#pragma once
// Wall-clock timers of the step stages, reported in summary.json under "timers".
#include <chrono>

namespace rockdd {

/// Seconds spent in each stage of the step loop.
struct StageTimers {
  double assembly = 0, factorization = 0, solve = 0, contact = 0, damage = 0, output = 0;
};

/// Adds the lifetime of the scope to one accumulator.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& seconds)
      : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace rockdd

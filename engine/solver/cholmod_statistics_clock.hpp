#pragma once
// CHOLMOD's statistics clock, stopped while rockdd factorizes.
//
// Debian's CHOLMOD is built with its CPU timing statistics (NTIMER undefined): its supernodal
// factorization reads the clock (SuiteSparse_time) around every BLAS call of every supernode,
// to add to cholmod_common's CHOLMOD_CPU_*_TIME, which rockdd never reads. The paper's
// compression specimen made 7.3 million such reads in one realization to 20 % softening,
// about 30 ns each on these machines: 2.3 % of perf's samples of the run. While a
// StoppedCholmodClock is alive on a thread, SuiteSparse_time returns 0 on that thread (the
// statistics then add zeros, and nothing else in CHOLMOD reads the clock); elsewhere, and on other
// threads, it is SuiteSparse's.

namespace rockdd {

/// Scope in which CHOLMOD's statistics clock reads 0 on this thread.
class StoppedCholmodClock {
 public:
  StoppedCholmodClock();
  ~StoppedCholmodClock();
  StoppedCholmodClock(const StoppedCholmodClock&) = delete;
  StoppedCholmodClock& operator=(const StoppedCholmodClock&) = delete;

  /// Whether the clock is stopped on this thread right now.
  static bool active();

 private:
  bool previous_;
};

}  // namespace rockdd

#pragma once
// rockdd mc's progress line on stderr, printed as each realization finishes and at least every
// 10 s between.
#include <string>
#include <vector>

namespace rockdd {

/// Where an ensemble run stands.
struct EnsembleProgress {
  long total = 0;          // seeds this run covers (its shard), rows of earlier runs included
  long done = 0;           // of them with a row
  long running = 0;        // realizations in worker processes now
  long failed = 0;         // of the done ones, not ok (crashed included)
  long finished_here = 0;  // realizations this run finished (the rate's count)
  double elapsed_s = 0.0;  // since this run started
  // For the ETA:
  long slots = 1;                    // realizations run at once (--jobs, times the MPI ranks)
  double mean_realization_s = 0.0;   // mean wall time of the realizations finished here
  std::vector<double> running_for;   // how long each running realization has run, s (those of
                                     // MPI peers, whose start is not known here, left out)
};

/// Seconds until the last realization ends: each running one needs the mean wall time less
/// what it has run (at least nothing), the ones not started go, one after another, to the
/// slot that frees first, and the ensemble ends when its last slot does. Negative (unknown)
/// before a realization finished here.
double ensemble_eta_seconds(const EnsembleProgress& p);

/// "mc: 5/8 done, 2 running, 0 failed, 412 realizations/h, ETA 00:01:10" (no newline); the
/// rate is this run's finished realizations over its elapsed time, the ETA
/// ensemble_eta_seconds(); both read "--" before its first realization finished.
std::string progress_line(const EnsembleProgress& p);

/// A duration as HH:MM:SS (hours may exceed 99).
std::string clock_time(double seconds);

}  // namespace rockdd

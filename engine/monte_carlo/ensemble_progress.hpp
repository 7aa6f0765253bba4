#pragma once
// rockdd mc's progress line on stderr, printed as each realization finishes.
#include <string>

namespace rockdd {

/// Where an ensemble run stands.
struct EnsembleProgress {
  long total = 0;          // seeds this run covers (its shard), rows of earlier runs included
  long done = 0;           // of them with a row
  long running = 0;        // realizations in worker processes now
  long failed = 0;         // of the done ones, not ok (crashed included)
  long finished_here = 0;  // realizations this run finished (the rate's count)
  double elapsed_s = 0.0;  // since this run started
};

/// "mc: 5/8 done, 2 running, 0 failed, 412 realizations/h, ETA 00:01:10" (no newline); the
/// rate and ETA are this run's, and read "--" before its first realization finished.
std::string progress_line(const EnsembleProgress& p);

/// A duration as HH:MM:SS (hours may exceed 99).
std::string clock_time(double seconds);

}  // namespace rockdd

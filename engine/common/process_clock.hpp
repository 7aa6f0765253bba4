#pragma once
// The age of the running process, so that a run can report the time spent before main():
// loading the shared libraries (Gmsh, CHOLMOD, TBB) and their static initialisation.
#include <optional>

namespace rockdd {

/// Seconds since this process started, from its start time in /proc/self/stat (kernel clock
/// ticks, 10 ms on Linux) and CLOCK_BOOTTIME; nullopt where /proc cannot be read.
std::optional<double> process_age_seconds();

}  // namespace rockdd

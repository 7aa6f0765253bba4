#pragma once
// The forked worker processes that run an ensemble's realizations, one process each.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/engine.hpp"
#include "engine/monte_carlo/monte_carlo.hpp"
#include "tools/monte_carlo_command.hpp"

namespace rockdd::cli {

/// Builds the model of the ensemble's first realization in a worker process, as `rockdd check`
/// does, before the ensemble makes a folder: bad input that every realization shares (a mesh
/// file that cannot be read, a .geo beyond the meshing budget, a boundary on a curve the mesh
/// lacks) throws its InputError here, exit 2 before a worker starts, instead of in each
/// worker. Other failures are left to the workers, whose rows record them. With the mesh
/// cache on, the workers then read the mesh from it.
void check_first_realization(const Scene& scene, const MonteCarloPlan& plan);

/// A realization that ended: its mc.csv row, or the bad input it found (the same for every
/// seed: no row).
struct FinishedRealization {
  std::uint64_t seed = 0;
  EnsembleRow row;
  std::optional<std::string> bad_input;
  double seconds = 0.0;  // wall time of its worker
};

/// Worker processes of one ensemble: each realization runs in a fork of this process (so that
/// each has the engine's process-wide settings to itself, and a crash takes only its own row).
/// The process that owns them runs no engine code: a fork would lose any thread pool it had.
class RealizationWorkers {
 public:
  RealizationWorkers(const Scene& scene, const MonteCarloPlan& plan,
                     std::vector<std::string> columns, int threads_per_run, FrameMode frames);
  ~RealizationWorkers();
  RealizationWorkers(const RealizationWorkers&) = delete;
  RealizationWorkers& operator=(const RealizationWorkers&) = delete;

  /// Starts realization `seed`; the worker closes `close_in_child` (the parent's lock and
  /// table, which a worker outliving a killed parent must not hold).
  void launch(std::uint64_t seed, const std::vector<int>& close_in_child = {});
  /// A worker that ended, reaped; waits for one when `block`. None when none has ended (or
  /// none runs).
  std::optional<FinishedRealization> reap(bool block);
  long running() const { return static_cast<long>(workers_.size()); }
  /// How long each running worker has run, s.
  std::vector<double> running_seconds() const;

 private:
  /// A realization running in a worker process.
  struct Worker {
    std::uint64_t seed = 0;
    int report_fd = -1;  // the read end of the worker's pipe
    std::chrono::steady_clock::time_point start;
  };
  EnsembleRow row_of(std::uint64_t seed, int status, const std::string& report) const;

  const Scene& scene_;
  const MonteCarloPlan& plan_;
  const std::vector<std::string> columns_;
  const int threads_per_run_;
  const FrameMode frames_;
  std::map<pid_t, Worker> workers_;
};

}  // namespace rockdd::cli

#pragma once
// rockdd mc and rockdd mc-merge: the ensemble's worker processes, its table and progress.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/engine.hpp"
#include "engine/monte_carlo/monte_carlo.hpp"

namespace rockdd::cli {

/// Which VTU frames a realization of an ensemble writes.
enum class FrameMode { none, last, all };

/// rockdd mc's command line.
struct MonteCarloOptions {
  std::string scene;
  std::vector<std::string> overrides;
  long realizations = 0;
  std::optional<std::uint64_t> first_seed;
  int threads = 0;  // 0: every hardware thread
  int jobs = 0;     // realizations at once; 0: one per thread
  std::optional<std::filesystem::path> out;
  Shard shard;
  bool restart = false;     // discard the rows of an earlier run
  bool frames = false;      // --frames: every VTU frame of every realization
  bool last_frame = true;   // each realization's last VTU frame (--no-last-frame: none)
  bool quiet = false;
  std::vector<std::string> command;  // the command line as given, for mc.provenance.json
};

/// The longest time between two progress lines written to a log (rockdd run off a terminal,
/// rockdd mc): 10 s, or $ROCKDD_PROGRESS_SECONDS when it is a positive number.
double progress_interval_seconds();

/// The VTU frames each realization of `options` writes.
FrameMode frame_mode(const MonteCarloOptions& options);

class EnsemblePeers;

/// Realizations at once in one process, and threads for each.
struct JobPlan {
  long jobs = 1;
  int threads_per_run = 1;
};

/// The jobs and threads of `options` for `todo` realizations: --jobs (default one per
/// thread), --threads (default every hardware thread) shared among them.
JobPlan plan_jobs(const MonteCarloOptions& options, long todo);

/// Runs the seeds of `options` that mc.csv has no completed row for, beside `peers` when
/// given (MPI ranks that take seeds too); returns the exit status: 0 every seed ok, 1 some
/// failed or crashed, 2 bad input.
int monte_carlo(const MonteCarloOptions& options, EnsemblePeers* peers = nullptr);

/// rockdd mc-merge OUTDIR DIR...; returns the exit status (bad input throws InputError).
int monte_carlo_merge(const std::filesystem::path& out_dir,
                      const std::vector<std::filesystem::path>& shard_dirs, bool quiet);

}  // namespace rockdd::cli

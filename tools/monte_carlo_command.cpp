#include "tools/monte_carlo_command.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iterator>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include "engine/common/atomic_file.hpp"
#include "engine/monte_carlo/ensemble_merge.hpp"
#include "engine/monte_carlo/ensemble_progress.hpp"
#include "engine/monte_carlo/ensemble_resume.hpp"
#include "engine/report/run_result.hpp"
#include "tools/ensemble_peers.hpp"
#include "tools/realization_workers.hpp"
#include "rockdd_git_commit.hpp"  // generated: ROCKDD_GIT_COMMIT

namespace rockdd::cli {
namespace {

using Clock = std::chrono::steady_clock;


double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// An exclusive lock on <dir>/mc.lock while this process lives (the kernel drops it when the
/// process dies, SIGKILL included): two runs appending to one mc.csv would run seeds twice.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& dir) {
    const std::filesystem::path file = dir / "mc.lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw std::runtime_error("cannot open '" + file.string() + "': " + strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw InputError(file.string(), "",
                       "another rockdd mc is running on this ensemble folder; wait for it to end "
                       "or give this run another --out");
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

/// The side of an ensemble run that owns mc.csv: it starts a worker process per realization
/// (RealizationWorkers), hands seeds to its peers (MPI ranks) when it has any, and appends each
/// finished realization's row to mc.csv, whichever process ran it.
class EnsembleRun {
 public:
  EnsembleRun(const MonteCarloOptions& options, Scene scene, MonteCarloPlan plan,
              EnsemblePeers* peers)
      : options_(options),
        scene_(std::move(scene)),
        plan_(std::move(plan)),
        identity_(ensemble_identity(scene_, options.overrides, plan_.first_seed)),
        columns_(ensemble_columns(scene_)),
        peers_(peers) {}

  /// Runs the seeds without a completed row; returns the exit status.
  int run() {
    std::filesystem::create_directories(plan_.dir);
    lock_ = std::make_unique<FolderLock>(plan_.dir);
    const EnsembleTable earlier = prepare_ensemble_folder(plan_.dir, identity_, columns_,
                                                          options_.restart, plan_.shard.text());
    const std::vector<std::uint64_t> seeds = plan_.seeds();
    const std::vector<std::uint64_t> todo = seeds_to_run(seeds, earlier.rows);
    for (const EnsembleRow& row : latest_rows(earlier.rows))
      if (row.completed() && std::binary_search(seeds.begin(), seeds.end(), row.seed))
        status_[row.seed] = row.status;
    appender_ = std::make_unique<EnsembleTableAppender>(plan_.dir / "mc.csv", columns_);
    jobs_ = plan_jobs(options_, static_cast<long>(todo.size()));
    record_provenance();
    workers_ = std::make_unique<RealizationWorkers>(scene_, plan_, columns_, jobs_.threads_per_run,
                                                    frame_mode(options_));
    announce(seeds, todo);
    if (peers_) peers_->begin(true);

    std::deque<std::uint64_t> queue(todo.begin(), todo.end());
    for (;;) {
      while (bad_input_.empty() && !queue.empty() && workers_->running() < jobs_.jobs) {
        launch(queue.front());
        queue.pop_front();
      }
      if (peers_)
        for (const FinishedRealization& done : peers_->poll(queue, !bad_input_.empty()))
          finish(done);
      const bool peers_done = !peers_ || peers_->finished();
      if (workers_->running() == 0 && peers_done && (queue.empty() || !bad_input_.empty())) break;
      // Look at the workers (and peers) every few milliseconds rather than wait for one: a
      // blocking MPI receive would spin a core that a realization needs, and a progress line
      // is due at least every kProgressInterval.
      if (const auto done = workers_->reap(false)) {
        finish(*done);
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(peers_ ? 5 : 50));
        if (!options_.quiet && seconds_since(last_line_) >= interval_) {
          std::fputs((progress_line(progress()) + "\n").c_str(), stderr);
          last_line_ = Clock::now();
        }
      }
    }
    if (!bad_input_.empty()) {
      std::cerr << "rockdd: error: " << bad_input_ << '\n';
      return 2;
    }
    compact();
    return conclude(static_cast<long>(seeds.size()));
  }

 private:
  void announce(const std::vector<std::uint64_t>& seeds, const std::vector<std::uint64_t>& todo) {
    if (options_.quiet) return;
    std::cerr << "rockdd mc: " << plan_.realizations << " realizations of " << scene_.name
              << ", seeds " << plan_.first_seed << ".." << plan_.seed(plan_.realizations - 1);
    if (!plan_.shard.text().empty())
      std::cerr << " (shard " << plan_.shard.text() << ": " << seeds.size() << " seeds)";
    std::cerr << "; " << seeds.size() - todo.size() << " already in "
              << (plan_.dir / "mc.csv").string() << ", " << todo.size() << " to run, " << jobs_.jobs
              << " at a time on " << jobs_.threads_per_run << " thread(s) each";
    if (peers_)
      std::cerr << " in each of " << peers_->count() + 1 << " MPI ranks (seeds go to the "
                << "first rank free)";
    std::cerr << '\n';
  }

  /// mc.provenance.json: the scene file (its path and text) and the overrides, and each run
  /// of the ensemble in this folder: its command line, start (UTC), rockdd's version and the
  /// commit it was built from, the host, jobs and threads. tools/plot ensemble --html shows it.
  /// A --restart begins the list anew.
  void record_provenance() const {
    const std::filesystem::path file = plan_.dir / "mc.provenance.json";
    nlohmann::json provenance;
    if (!options_.restart) {
      std::ifstream in(file);
      try {
        if (in) provenance = nlohmann::json::parse(in);
      } catch (const nlohmann::json::exception&) {
        provenance = nullptr;  // written anew below
      }
    }
    if (!provenance.is_object() || !provenance.contains("runs") || !provenance["runs"].is_array())
      provenance = {{"runs", nlohmann::json::array()}};
    std::ifstream scene_in(scene_.file, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(scene_in), {}};
    provenance["scene"] = scene_.name;
    provenance["scene_file"] = scene_.file.string();
    provenance["scene_text"] = text;
    provenance["overrides"] = options_.overrides;
    provenance["first_seed"] = plan_.first_seed;
    const std::time_t now = std::time(nullptr);
    char started[32];
    std::strftime(started, sizeof started, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    char host[256] = "";
    ::gethostname(host, sizeof host - 1);
    provenance["runs"].push_back({{"command", options_.command},
                                  {"started", started},
                                  {"rockdd_version", ROCKDD_VERSION},
                                  {"commit", ROCKDD_GIT_COMMIT},
                                  {"host", host},
                                  {"realizations", plan_.realizations},
                                  {"shard", plan_.shard.text()},
                                  {"jobs", jobs_.jobs},
                                  {"threads_per_run", jobs_.threads_per_run}});
    write_file_atomically(file, provenance.dump(2) + "\n");
  }

  void launch(std::uint64_t seed) { workers_->launch(seed, {appender_->fd(), lock_->fd()}); }

  void finish(const FinishedRealization& done) {
    if (done.bad_input) {
      bad_input_ = *done.bad_input;  // the same for every seed: no row, and no further launches
      return;
    }
    const EnsembleRow& row = done.row;
    appender_->append(row);
    write_ensemble_report(plan_.dir, identity_);
    status_[row.seed] = row.status;
    ++finished_here_;
    seconds_here_ += done.seconds;
    if (options_.quiet) return;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.1f", done.seconds);
    std::string line = "mc: seed " + std::to_string(row.seed) + ": " + row.status;
    if (!row.reason.empty()) line += ": " + row.reason;
    line += " (" + std::string(seconds) + " s)\n" + progress_line(progress()) + "\n";
    std::fputs(line.c_str(), stderr);
    last_line_ = Clock::now();
  }

  EnsembleProgress progress() const {
    EnsembleProgress p;
    p.total = static_cast<long>(plan_.seeds().size());
    p.done = static_cast<long>(status_.size());
    p.running = workers_->running() + (peers_ ? peers_->running() : 0);
    p.failed = failed();
    p.finished_here = finished_here_;
    p.elapsed_s = seconds_since(start_);
    p.slots = jobs_.jobs * (peers_ ? peers_->count() + 1 : 1);
    p.mean_realization_s = finished_here_ > 0 ? seconds_here_ / finished_here_ : 0.0;
    p.running_for = workers_->running_seconds();
    return p;
  }

  long failed() const {
    return std::count_if(status_.begin(), status_.end(),
                         [](const auto& s) { return s.second != "ok"; });
  }

  /// mc.csv rewritten with the last row of each seed, sorted by seed (rows arrive in the
  /// order realizations finish, and a re-run seed has its crashed row before the new one).
  void compact() {
    appender_.reset();
    const std::filesystem::path csv = plan_.dir / "mc.csv";
    EnsembleTable table = read_ensemble_table(csv);
    table.rows = latest_rows(table.rows);
    write_ensemble_table(csv, table);
    write_ensemble_report(plan_.dir, identity_);
  }

  int conclude(long total) const {
    const long bad = failed();
    if (!options_.quiet)
      std::cerr << "rockdd mc: " << static_cast<long>(status_.size()) - bad << " ok, " << bad
                << " failed or crashed of " << total << "; table in "
                << (plan_.dir / "mc.csv").string() << ", statistics in "
                << (plan_.dir / "mc.json").string() << '\n';
    return bad > 0 || static_cast<long>(status_.size()) < total ? 1 : 0;
  }

  const MonteCarloOptions& options_;
  const Scene scene_;
  const MonteCarloPlan plan_;
  const EnsembleIdentity identity_;
  const std::vector<std::string> columns_;
  EnsemblePeers* const peers_;
  std::unique_ptr<FolderLock> lock_;
  std::unique_ptr<EnsembleTableAppender> appender_;
  JobPlan jobs_;
  std::unique_ptr<RealizationWorkers> workers_;
  std::map<std::uint64_t, std::string> status_;  // the status of each of this run's seeds done
  long finished_here_ = 0;
  double seconds_here_ = 0.0;  // the wall times of the realizations finished here, summed
  std::string bad_input_;  // the message of a worker that found bad input
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_line_ = Clock::now();  // the last progress line printed
  const double interval_ = progress_interval_seconds();
};

}  // namespace

double progress_interval_seconds() {
  if (const char* text = std::getenv("ROCKDD_PROGRESS_SECONDS")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && *end == '\0' && seconds > 0 && seconds < 1e9) return seconds;
  }
  return 10.0;
}

FrameMode frame_mode(const MonteCarloOptions& options) {
  if (options.frames) return FrameMode::all;
  return options.last_frame ? FrameMode::last : FrameMode::none;
}

JobPlan plan_jobs(const MonteCarloOptions& options, long todo) {
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = options.threads > 0 ? options.threads : hardware;
  JobPlan plan;
  plan.jobs =
      std::max(1L, std::min(todo, static_cast<long>(options.jobs > 0 ? options.jobs : threads)));
  plan.threads_per_run = std::max(1, threads / static_cast<int>(plan.jobs));
  return plan;
}

int monte_carlo(const MonteCarloOptions& options, EnsemblePeers* peers) {
  Scene scene = load_scene(options.scene, options.overrides);
  MonteCarloPlan plan =
      plan_monte_carlo(scene, options.realizations, options.first_seed,
                       options.out.value_or(std::filesystem::path()), options.shard);
  check_first_realization(scene, plan);  // exit 2 before a folder or a worker, not "crashed"
  return EnsembleRun(options, std::move(scene), std::move(plan), peers).run();
}

int monte_carlo_merge(const std::filesystem::path& out_dir,
                      const std::vector<std::filesystem::path>& shard_dirs, bool quiet) {
  const nlohmann::json report = merge_ensembles(out_dir, shard_dirs);
  if (!quiet)
    std::cerr << "rockdd mc-merge: " << report["realizations"] << " realizations from "
              << shard_dirs.size() << " folders, " << report["ok"] << " ok; table in "
              << (out_dir / "mc.csv").string() << ", statistics in "
              << (out_dir / "mc.json").string() << '\n';
  return 0;
}

}  // namespace rockdd::cli

#include "tools/monte_carlo_command.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include "engine/monte_carlo/ensemble_merge.hpp"
#include "engine/monte_carlo/ensemble_progress.hpp"
#include "engine/monte_carlo/ensemble_resume.hpp"

namespace rockdd::cli {
namespace {

using Clock = std::chrono::steady_clock;

/// Exit statuses of a worker process.
enum WorkerExit : int { kOk = 0, kFailed = 1, kBadInput = 2, kCrashed = 3 };

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

/// In a worker: the text of an exception, for the parent to put in the row (one write into
/// a pipe it reads once the worker has ended; short enough never to block).
void report_to_parent(int fd, const std::string& message) {
  const std::string text = message.substr(0, 4000);
  [[maybe_unused]] const ssize_t ignored = ::write(fd, text.data(), text.size());
}

/// Everything a finished worker wrote into its pipe.
std::string read_report(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

/// In a worker: realization `seed` into its folder; returns the worker's exit status.
int run_realization(const Scene& scene, const MonteCarloPlan& plan, std::uint64_t seed, int threads,
                    bool frames, int report_fd) {
  try {
    const Scene realization = realization_scene(scene, seed);
    Simulation sim(realization, build_scene_model(realization));
    RunOptions options;
    options.out_dir = plan.realization_dir(seed);
    options.threads = threads;
    options.write_frames = frames;
    return sim.run(options).ok ? kOk : kFailed;
  } catch (const InputError& e) {
    report_to_parent(report_fd, e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    report_to_parent(report_fd, e.what());
    return kCrashed;
  }
}

/// The summary.json a realization left; null when there is none to read.
nlohmann::json read_summary(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

/// The parent's side of an ensemble run: it forks a worker per realization (so that each has
/// the engine's process-wide settings to itself, and a crash takes only its own row), and
/// appends each finished realization's row to mc.csv. The parent runs no engine code: a fork
/// would lose any thread pool it had started.
class EnsembleRun {
 public:
  EnsembleRun(const MonteCarloOptions& options, Scene scene, MonteCarloPlan plan)
      : options_(options),
        scene_(std::move(scene)),
        plan_(std::move(plan)),
        identity_(ensemble_identity(scene_, options.overrides, plan_.first_seed)),
        columns_(ensemble_columns(scene_)) {}

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
    plan_jobs(static_cast<long>(todo.size()));
    announce(seeds, todo);

    std::deque<std::uint64_t> queue(todo.begin(), todo.end());
    while (!queue.empty() || !workers_.empty()) {
      while (bad_input_.empty() && !queue.empty() && static_cast<long>(workers_.size()) < jobs_) {
        launch(queue.front());
        queue.pop_front();
      }
      if (workers_.empty()) break;
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, 0);
      if (pid < 0 && errno == EINTR) continue;
      if (pid < 0) throw std::runtime_error(std::string("mc: waitpid: ") + strerror(errno));
      finish(pid, status);
    }
    if (!bad_input_.empty()) {
      std::cerr << "rockdd: error: " << bad_input_ << '\n';
      return 2;
    }
    compact();
    return conclude(static_cast<long>(seeds.size()));
  }

 private:
  /// A realization running in a worker process.
  struct Worker {
    std::uint64_t seed = 0;
    int report_fd = -1;  // the read end of the worker's pipe
    Clock::time_point start;
  };

  void plan_jobs(long todo) {
    const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int threads = options_.threads > 0 ? options_.threads : hardware;
    jobs_ = std::max(
        1L, std::min(todo, static_cast<long>(options_.jobs > 0 ? options_.jobs : threads)));
    threads_per_run_ = std::max(1, threads / static_cast<int>(jobs_));
  }

  void announce(const std::vector<std::uint64_t>& seeds, const std::vector<std::uint64_t>& todo) {
    if (options_.quiet) return;
    std::cerr << "rockdd mc: " << plan_.realizations << " realizations of " << scene_.name
              << ", seeds " << plan_.first_seed << ".." << plan_.seed(plan_.realizations - 1);
    if (!plan_.shard.text().empty())
      std::cerr << " (shard " << plan_.shard.text() << ": " << seeds.size() << " seeds)";
    std::cerr << "; " << seeds.size() - todo.size() << " already in "
              << (plan_.dir / "mc.csv").string() << ", " << todo.size() << " to run, " << jobs_
              << " at a time on " << threads_per_run_ << " thread(s) each\n";
  }

  void launch(std::uint64_t seed) {
    // A summary.json of an earlier attempt must not pass for this one's.
    std::filesystem::remove(plan_.realization_dir(seed) / "summary.json");
    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
      throw std::runtime_error(std::string("mc: pipe: ") + strerror(errno));
    std::fflush(nullptr);  // no buffered output copied into the child
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error(std::string("mc: fork: ") + strerror(errno));
    if (pid == 0) {
      // A worker dies with the parent: an orphan would go on writing into a seed folder that
      // the next run of the ensemble runs again.
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(kCrashed);
      ::close(pipe_fds[0]);
      ::close(appender_->fd());
      ::close(lock_->fd());
      const int code =
          run_realization(scene_, plan_, seed, threads_per_run_, options_.frames, pipe_fds[1]);
      std::fflush(nullptr);
      ::_exit(code);
    }
    ::close(pipe_fds[1]);
    workers_[pid] = {seed, pipe_fds[0], Clock::now()};
  }

  /// The row of a worker that ended with `status` after reporting `report`.
  EnsembleRow row_of(std::uint64_t seed, int status, const std::string& report) const {
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == kOk || code == kFailed) {
      const nlohmann::json summary = read_summary(plan_.realization_dir(seed) / "summary.json");
      if (summary.is_object()) return realization_row(columns_, seed, summary);
      return crashed_row(columns_, seed, "the run left no readable summary.json");
    }
    if (WIFSIGNALED(status))
      return crashed_row(columns_, seed,
                         "worker killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
                             strsignal(WTERMSIG(status)) + ")");
    if (code == kCrashed && !report.empty()) return crashed_row(columns_, seed, report);
    return crashed_row(columns_, seed, "worker exited with status " + std::to_string(code));
  }

  void finish(pid_t pid, int status) {
    const auto found = workers_.find(pid);
    if (found == workers_.end()) return;
    const Worker worker = found->second;
    workers_.erase(found);
    const std::string report = read_report(worker.report_fd);
    ::close(worker.report_fd);
    if (WIFEXITED(status) && WEXITSTATUS(status) == kBadInput) {
      bad_input_ = report;  // the same for every seed: no row, and no further launches
      return;
    }
    const EnsembleRow row = row_of(worker.seed, status, report);
    appender_->append(row);
    write_ensemble_report(plan_.dir, identity_);
    status_[worker.seed] = row.status;
    ++finished_here_;
    if (options_.quiet) return;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.1f", seconds_since(worker.start));
    std::string line = "mc: seed " + std::to_string(worker.seed) + ": " + row.status;
    if (!row.reason.empty()) line += ": " + row.reason;
    line += " (" + std::string(seconds) + " s)\n" + progress_line(progress()) + "\n";
    std::fputs(line.c_str(), stderr);
  }

  EnsembleProgress progress() const {
    EnsembleProgress p;
    p.total = static_cast<long>(plan_.seeds().size());
    p.done = static_cast<long>(status_.size());
    p.running = static_cast<long>(workers_.size());
    p.failed = failed();
    p.finished_here = finished_here_;
    p.elapsed_s = seconds_since(start_);
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
  std::unique_ptr<FolderLock> lock_;
  std::unique_ptr<EnsembleTableAppender> appender_;
  long jobs_ = 1;
  int threads_per_run_ = 1;
  std::map<pid_t, Worker> workers_;
  std::map<std::uint64_t, std::string> status_;  // the status of each of this run's seeds done
  long finished_here_ = 0;
  std::string bad_input_;  // the message of a worker that found bad input
  Clock::time_point start_ = Clock::now();
};

}  // namespace

int monte_carlo(const MonteCarloOptions& options) {
  Scene scene = load_scene(options.scene, options.overrides);
  MonteCarloPlan plan =
      plan_monte_carlo(scene, options.realizations, options.first_seed,
                       options.out.value_or(std::filesystem::path()), options.shard);
  return EnsembleRun(options, std::move(scene), std::move(plan)).run();
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

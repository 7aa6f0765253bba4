#include "tools/realization_workers.hpp"
#include "engine/report/run_result.hpp"

#include <fcntl.h>
#include <oneapi/tbb/global_control.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace rockdd::cli {
namespace {

using Clock = std::chrono::steady_clock;

/// Exit statuses of a worker process.
enum WorkerExit : int { kOk = 0, kFailed = 1, kBadInput = 2, kCrashed = 3 };

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
                    FrameMode frames, int report_fd) {
  try {
    std::optional<tbb::global_control> parallelism;  // the model and set-up too
    if (threads > 0)
      parallelism.emplace(tbb::global_control::max_allowed_parallelism,
                          static_cast<std::size_t>(threads));
    Scene realization = realization_scene(scene, seed);
    // The last frame only: kept in memory as the run goes and written when it ends (one
    // compressed frame for the crack pattern, not one every output.every steps).
    realization.output.last_frame_only = frames == FrameMode::last;
    Simulation sim(realization, build_scene_model(realization));
    RunOptions options;
    options.out_dir = plan.realization_dir(seed);
    options.threads = threads;
    options.write_frames = frames != FrameMode::none;
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

/// In a worker: an InputError as the three fields the parent rebuilds it from, 0-separated.
std::string input_error_report(const InputError& error) {
  return error.where() + '\0' + error.key() + '\0' + error.expected();
}

/// A pipe whose ends close on exec, for a child's report to the parent.
void open_report_pipe(int (&fds)[2]) {
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("mc: pipe: ") + strerror(errno));
}

/// Forks a child that dies with this process and shows as `name` in ps and top (the kernel
/// keeps 15 characters): its pid in the parent, 0 in the child.
pid_t fork_named_child(const std::string& name) {
  std::fflush(nullptr);  // no buffered output copied into the child
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("mc: fork: ") + strerror(errno));
  if (pid == 0) {
    // An orphan worker would go on writing into a seed folder that the next run of the
    // ensemble runs again.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(kCrashed);
    ::prctl(PR_SET_NAME, name.c_str());
  }
  return pid;
}

}  // namespace

void check_first_realization(const Scene& scene, const MonteCarloPlan& plan) {
  int pipe_fds[2];
  open_report_pipe(pipe_fds);
  const pid_t pid = fork_named_child("rockdd check");
  if (pid == 0) {
    ::close(pipe_fds[0]);
    int code = kOk;
    try {
      const Scene realization = realization_scene(scene, plan.seed(0));
      const Simulation sim(realization, build_scene_model(realization));
    } catch (const InputError& e) {
      report_to_parent(pipe_fds[1], input_error_report(e));
      code = kBadInput;
    } catch (const std::exception&) {
      code = kCrashed;  // the workers meet it again and record it in their rows
    }
    std::fflush(nullptr);
    ::_exit(code);
  }
  ::close(pipe_fds[1]);
  const std::string report = read_report(pipe_fds[0]);
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != kBadInput) return;
  const std::size_t key = report.find('\0'), expected = report.find('\0', key + 1);
  if (key == std::string::npos || expected == std::string::npos)
    throw InputError(scene.file.string(), "", report);
  throw InputError(report.substr(0, key), report.substr(key + 1, expected - key - 1),
                   report.substr(expected + 1));
}

RealizationWorkers::RealizationWorkers(const Scene& scene, const MonteCarloPlan& plan,
                                       std::vector<std::string> columns, int threads_per_run,
                                       FrameMode frames)
    : scene_(scene),
      plan_(plan),
      columns_(std::move(columns)),
      threads_per_run_(threads_per_run),
      frames_(frames) {}

RealizationWorkers::~RealizationWorkers() {
  for (const auto& [pid, worker] : workers_) ::close(worker.report_fd);
}

void RealizationWorkers::launch(std::uint64_t seed, const std::vector<int>& close_in_child) {
  // A summary.json of an earlier attempt must not pass for this one's.
  std::filesystem::remove(plan_.realization_dir(seed) / "summary.json");
  int pipe_fds[2];
  open_report_pipe(pipe_fds);
  const pid_t pid = fork_named_child("seed " + std::to_string(seed));
  if (pid == 0) {
    ::close(pipe_fds[0]);
    for (const int fd : close_in_child) ::close(fd);
    const int code = run_realization(scene_, plan_, seed, threads_per_run_, frames_, pipe_fds[1]);
    std::fflush(nullptr);
    ::_exit(code);
  }
  ::close(pipe_fds[1]);
  workers_[pid] = {seed, pipe_fds[0], Clock::now()};
}

EnsembleRow RealizationWorkers::row_of(std::uint64_t seed, int status,
                                       const std::string& report) const {
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

std::vector<double> RealizationWorkers::running_seconds() const {
  std::vector<double> seconds;
  const auto now = Clock::now();
  for (const auto& [pid, worker] : workers_)
    seconds.push_back(std::chrono::duration<double>(now - worker.start).count());
  return seconds;
}

std::optional<FinishedRealization> RealizationWorkers::reap(bool block) {
  while (!workers_.empty()) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, block ? 0 : WNOHANG);
    if (pid < 0 && errno == EINTR) continue;
    if (pid < 0) throw std::runtime_error(std::string("mc: waitpid: ") + strerror(errno));
    if (pid == 0) return std::nullopt;  // none has ended yet
    const auto found = workers_.find(pid);
    if (found == workers_.end()) continue;
    const Worker worker = found->second;
    workers_.erase(found);
    const std::string report = read_report(worker.report_fd);
    ::close(worker.report_fd);
    FinishedRealization done;
    done.seed = worker.seed;
    done.seconds = std::chrono::duration<double>(Clock::now() - worker.start).count();
    if (WIFEXITED(status) && WEXITSTATUS(status) == kBadInput)
      done.bad_input = report;
    else
      done.row = row_of(worker.seed, status, report);
    return done;
  }
  return std::nullopt;
}

}  // namespace rockdd::cli

// rockdd command line: a thin client of the engine library (engine/rockdd.hpp).
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "engine/rockdd.hpp"

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  rockdd run SCENE [--out DIR] [--threads N] [--set key.path=value ...] [--quiet]\n"
    "  rockdd check SCENE [--set key.path=value ...]\n"
    "  rockdd mc SCENE --realizations N [--first-seed S] [--threads N] [--jobs J]\n"
    "                  [--out DIR] [--set key.path=value ...] [--quiet]\n"
    "  rockdd --version | --help\n"
    "exit status: 0 success, 1 the run failed numerically, 2 bad input\n";

/// Parsed command line.
struct Command {
  std::string verb, scene;
  std::optional<std::string> out;
  int threads = 0;
  bool quiet = false;
  std::vector<std::string> overrides;
  long realizations = 0;
  std::optional<long> first_seed;
  int jobs = 0;  // mc: realizations run at once (0: one per thread)
};

/// Bad command line: usage error, exit 2.
struct UsageError {
  std::string message;
};

long parse_integer(const std::string& flag, const char* text, long min) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*text == '\0' || *end != '\0' || value < min)
    throw UsageError{flag + " expects an integer >= " + std::to_string(min) + ", got '" + text +
                     "'"};
  return value;
}

Command parse_command_line(int argc, char** argv) {
  if (argc < 2) throw UsageError{"missing command"};
  Command cmd;
  cmd.verb = argv[1];
  if (cmd.verb != "run" && cmd.verb != "check" && cmd.verb != "mc")
    throw UsageError{"unknown command '" + cmd.verb + "'"};
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError{arg + " needs a value"};
      return argv[++i];
    };
    if (arg == "--out")
      cmd.out = value();
    else if (arg == "--threads")
      cmd.threads = static_cast<int>(parse_integer(arg, value(), 1));
    else if (arg == "--set")
      cmd.overrides.emplace_back(value());
    else if (arg == "--quiet")
      cmd.quiet = true;
    else if (arg == "--realizations")
      cmd.realizations = parse_integer(arg, value(), 1);
    else if (arg == "--first-seed")
      cmd.first_seed = parse_integer(arg, value(), 0);
    else if (arg == "--jobs")
      cmd.jobs = static_cast<int>(parse_integer(arg, value(), 1));
    else if (!arg.empty() && arg[0] == '-')
      throw UsageError{"unknown option '" + arg + "'"};
    else if (cmd.scene.empty())
      cmd.scene = arg;
    else
      throw UsageError{"unexpected argument '" + arg + "'"};
  }
  if (cmd.scene.empty()) throw UsageError{"missing SCENE file"};
  if (cmd.verb == "mc" && cmd.realizations == 0) throw UsageError{"mc needs --realizations N"};
  if (cmd.verb != "mc" && (cmd.realizations > 0 || cmd.first_seed || cmd.jobs > 0))
    throw UsageError{"--realizations, --first-seed and --jobs belong to mc"};
  return cmd;
}

/// Progress on a terminal (one rewritten line) or plain log lines every 10 %.
class Progress {
 public:
  Progress(bool quiet) : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(const rockdd::StepReport& r) {
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double fraction = r.end_time > 0 ? r.time / r.end_time : 1.0;
    const bool done = fraction >= 1.0 - 1e-12;
    if (tty_) {
      if (!done && std::chrono::duration<double>(now - last_).count() < 0.1) return;
      last_ = now;
      const int width = 30, filled = static_cast<int>(std::lround(fraction * width));
      const double rate = r.step / std::max(elapsed, 1e-9);
      const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
      std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  t = %.4g s  step %ld  %.0f steps/s  ETA %.0f s ",
                   filled, "##############################", width - filled, "", 100 * fraction,
                   r.time, r.step, rate, eta);
      if (done) std::fputc('\n', stderr);
    } else {
      const int decile = static_cast<int>(std::floor(fraction * 10 + 1e-9));
      if (decile <= last_decile_ && !done) return;
      if (done && last_decile_ >= 10) return;
      last_decile_ = decile;
      std::fprintf(stderr, "rockdd: step %ld  t = %.6g s  (%d%%)  %.2f s elapsed\n", r.step, r.time,
                   std::min(100, decile * 10), elapsed);
    }
  }

 private:
  bool quiet_, tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

int run(const Command& cmd) {
  rockdd::Scene scene = rockdd::load_scene(cmd.scene, cmd.overrides);
  rockdd::Simulation sim(scene, rockdd::build_scene_model(scene));
  Progress progress(cmd.quiet);
  rockdd::RunOptions options;
  if (cmd.out) options.out_root = *cmd.out;
  options.threads = cmd.threads;
  options.on_step = [&](const rockdd::StepReport& r, const rockdd::Model&) { progress(r); };
  const rockdd::RunResult result = sim.run(options);
  const auto out_dir =
      (options.out_root.empty() ? scene.output.dir : options.out_root) / scene.name;
  if (!result.ok) {
    std::cerr << "rockdd: run failed: " << result.reason << "\n  outputs so far in "
              << out_dir.string() << "\n";
    return 1;
  }
  if (!cmd.quiet)
    std::cerr << "rockdd: ok: " << result.summary["steps"] << " steps, "
              << result.summary["elements"] << " elements, " << result.summary["blocks"]
              << " blocks, " << result.summary["wall_seconds"].get<double>() << " s; outputs in "
              << out_dir.string() << "\n";
  return 0;
}

/// Runs realization `r` of a Monte Carlo plan into its folder; prints one line on stderr.
/// Returns false when it failed numerically.
bool run_realization(const rockdd::Scene& scene, const rockdd::MonteCarloPlan& plan, long r,
                     int threads, bool quiet) {
  const std::uint64_t seed = plan.seed(r);
  const rockdd::Scene realization = rockdd::realization_scene(scene, seed);
  rockdd::Simulation sim(realization, rockdd::build_scene_model(realization));
  rockdd::RunOptions options;
  options.out_dir = plan.realization_dir(seed);
  options.threads = threads;
  const rockdd::RunResult result = sim.run(options);
  if (!quiet) {
    const std::string line = "rockdd mc: seed " + std::to_string(seed) + ": " +
                             (result.ok ? "ok" : "failed: " + result.reason) + " (" +
                             std::to_string(result.summary["wall_seconds"].get<double>()) + " s)\n";
    std::fputs(line.c_str(), stderr);  // one write per line: workers do not interleave
  }
  return result.ok;
}

/// Monte Carlo over seeds: `jobs` worker processes (a fork each, so that every realization
/// has the engine's process-wide settings to itself) share the realizations round-robin;
/// the parent then gathers the summaries into mc.csv and mc.json.
int monte_carlo(const Command& cmd) {
  const rockdd::Scene scene = rockdd::load_scene(cmd.scene, cmd.overrides);
  const rockdd::MonteCarloPlan plan = rockdd::plan_monte_carlo(
      scene, cmd.realizations,
      cmd.first_seed ? std::optional<std::uint64_t>(static_cast<std::uint64_t>(*cmd.first_seed))
                     : std::nullopt,
      cmd.out ? std::filesystem::path(*cmd.out) : std::filesystem::path());
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = cmd.threads > 0 ? cmd.threads : hardware;
  const int jobs =
      static_cast<int>(std::min<long>(cmd.realizations, cmd.jobs > 0 ? cmd.jobs : threads));
  const int threads_per_run = std::max(1, threads / jobs);
  std::filesystem::create_directories(plan.dir);
  if (!cmd.quiet)
    std::cerr << "rockdd mc: " << cmd.realizations << " realizations of " << scene.name
              << ", seeds " << plan.first_seed << ".." << plan.seed(cmd.realizations - 1) << ", "
              << jobs << " at a time on " << threads_per_run << " thread(s) each\n";
  // The parent has run no engine code yet (no thread pools to lose in a fork).
  std::vector<pid_t> workers;
  for (int w = 0; w < jobs && jobs > 1; ++w) {
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("mc: fork failed");
    if (pid == 0) {
      int status = 0;
      // A realization that throws leaves no summary.json (mc.csv reports it as crashed);
      // the worker goes on with its other realizations. Bad input stops it: it is the
      // same for every seed.
      for (long r = w; r < cmd.realizations && status != 2; r += jobs) {
        try {
          run_realization(scene, plan, r, threads_per_run, cmd.quiet);
        } catch (const rockdd::InputError& e) {
          std::cerr << "rockdd: error: " << e.what() << '\n';
          status = 2;
        } catch (const std::exception& e) {
          std::cerr << "rockdd mc: seed " << plan.seed(r) << ": " << e.what() << '\n';
          status = 1;
        }
      }
      std::fflush(stderr);
      _exit(status);
    }
    workers.push_back(pid);
  }
  if (jobs == 1)
    for (long r = 0; r < cmd.realizations; ++r)
      run_realization(scene, plan, r, threads_per_run, cmd.quiet);
  bool bad_input = false;
  for (const pid_t pid : workers) {
    int status = 0;
    waitpid(pid, &status, 0);
    bad_input = bad_input || (WIFEXITED(status) && WEXITSTATUS(status) == 2);
  }
  if (bad_input) return 2;
  const nlohmann::json report = rockdd::write_monte_carlo_report(scene, plan);
  const long failed = report["failed"].get<long>();
  if (!cmd.quiet)
    std::cerr << "rockdd mc: " << report["ok"].get<long>() << " ok, " << failed
              << " failed; table in " << (plan.dir / "mc.csv").string() << ", statistics in "
              << (plan.dir / "mc.json").string() << '\n';
  return failed > 0 ? 1 : 0;
}

int check(const Command& cmd) {
  const rockdd::Scene scene = rockdd::load_scene(cmd.scene, cmd.overrides);
  rockdd::Simulation sim(scene, rockdd::build_scene_model(scene));
  const rockdd::Model& model = sim.model();
  std::cout << "scene: " << scene.name << " (" << scene.file.string() << ")\n"
            << "elements: " << model.num_elements() << "\nnodes: " << model.num_nodes()
            << "\nblocks: " << model.num_blocks << "\nbodies:";
  for (const auto& b : model.sets.bodies) std::cout << " '" << b << "'";
  std::cout << "\ncurves:";
  for (const auto& [name, edges] : model.sets.curve_edges)
    std::cout << ' ' << name << '(' << edges.size() / 2 << ')';
  std::cout << "\npoints:";
  for (const auto& [name, nodes] : model.sets.points) std::cout << ' ' << name;
  std::cout << "\ndefaults:\n";
  for (const auto& [key, value] : scene.defaults)
    std::cout << "  " << key << " = " << value << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::cout << kUsage;
    return 0;
  }
  if (argc >= 2 && std::strcmp(argv[1], "--version") == 0) {
    std::cout << "rockdd " << rockdd::version() << '\n';
    return 0;
  }
  try {
    const Command cmd = parse_command_line(argc, argv);
    if (cmd.verb == "run") return run(cmd);
    if (cmd.verb == "check") return check(cmd);
    return monte_carlo(cmd);
  } catch (const UsageError& e) {
    std::cerr << "rockdd: " << e.message << '\n' << kUsage;
    return 2;
  } catch (const rockdd::InputError& e) {
    std::cerr << "rockdd: error: " << e.what() << '\n';
    return 2;
  } catch (const rockdd::RunFailure& e) {
    std::cerr << "rockdd: run failed: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rockdd: " << e.what() << '\n';
    return 1;
  }
}

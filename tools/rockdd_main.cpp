// rockdd command line: a thin client of the engine library (engine/rockdd.hpp).
#include <oneapi/tbb/global_control.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/common/process_clock.hpp"
#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"
#include "engine/scene/step_budget.hpp"
#include "tools/monte_carlo_command.hpp"
#ifdef ROCKDD_HAVE_MPI
#include "tools/mpi_ensemble.hpp"
#endif

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  rockdd run SCENE [--out DIR] [--threads N] [--set key.path=value ...] [--quiet]\n"
    "                   [--mesh-cache DIR|off]\n"
    "  rockdd check SCENE [--set key.path=value ...]\n"
    "  rockdd mc SCENE --realizations N [--first-seed S] [--threads N] [--jobs J]\n"
    "                  [--out DIR] [--shard I/N] [--restart] [--frames]\n"
    "                  [--set key.path=value ...] [--quiet]\n"
    "  mpirun -n K rockdd mc ...              # K ranks share the seeds (an MPI build)\n"
    "  rockdd mc-merge OUTDIR DIR1 DIR2 ...   # join the shards' mc.csv into OUTDIR\n"
    "  rockdd --version | --help\n"
    "--mesh-cache DIR|off (run, check, mc): where meshes are kept between runs (default\n"
    "  $ROCKDD_MESH_CACHE, else $XDG_CACHE_HOME/rockdd/meshes or ~/.cache/rockdd/meshes)\n"
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
  std::optional<rockdd::Shard> shard;
  bool restart = false, frames = false;
  std::vector<std::string> folders;       // mc-merge: OUTDIR then the shard folders
  std::optional<std::string> mesh_cache;  // --mesh-cache: a folder, or "off"
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

/// --shard I/N: part I (1-based) of N.
rockdd::Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  const auto number = [](const std::string& part) -> long {
    char* end = nullptr;
    const long value = std::strtol(part.c_str(), &end, 10);
    return part.empty() || *end != '\0' ? 0 : value;
  };
  if (slash != std::string::npos) {
    const long i = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
    if (n >= 1 && i >= 1 && i <= n) return {i, n};
  }
  throw UsageError{"--shard expects I/N with 1 <= I <= N (part I of N), got '" + text + "'"};
}

Command parse_command_line(int argc, char** argv) {
  if (argc < 2) throw UsageError{"missing command"};
  Command cmd;
  cmd.verb = argv[1];
  if (cmd.verb != "run" && cmd.verb != "check" && cmd.verb != "mc" && cmd.verb != "mc-merge")
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
    else if (arg == "--shard")
      cmd.shard = parse_shard(value());
    else if (arg == "--restart")
      cmd.restart = true;
    else if (arg == "--frames")
      cmd.frames = true;
    else if (arg == "--mesh-cache")
      cmd.mesh_cache = value();
    else if (!arg.empty() && arg[0] == '-')
      throw UsageError{"unknown option '" + arg + "'"};
    else if (cmd.verb == "mc-merge")
      cmd.folders.push_back(arg);
    else if (cmd.scene.empty())
      cmd.scene = arg;
    else
      throw UsageError{"unexpected argument '" + arg + "'"};
  }
  if (cmd.verb == "mc-merge") {
    if (cmd.folders.size() < 2) throw UsageError{"mc-merge needs OUTDIR and at least one DIR"};
    if (cmd.realizations > 0 || cmd.first_seed || cmd.jobs > 0 || cmd.shard || cmd.restart ||
        cmd.frames || cmd.mesh_cache || cmd.out || cmd.threads > 0 || !cmd.overrides.empty())
      throw UsageError{"mc-merge takes only OUTDIR, the shard folders and --quiet"};
    return cmd;
  }
  if (cmd.scene.empty()) throw UsageError{"missing SCENE file"};
  if (cmd.verb == "mc" && cmd.realizations == 0) throw UsageError{"mc needs --realizations N"};
  if (cmd.verb != "mc" && (cmd.realizations > 0 || cmd.first_seed || cmd.jobs > 0 || cmd.shard ||
                           cmd.restart || cmd.frames))
    throw UsageError{
        "--realizations, --first-seed, --jobs, --shard, --restart and --frames belong to mc"};
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

int run(const Command& cmd, std::optional<double> startup) {
  // --threads bounds the whole run: the model and the simulation's set-up too, not only its
  // steps (RunOptions::threads).
  std::optional<tbb::global_control> parallelism;
  if (cmd.threads > 0)
    parallelism.emplace(tbb::global_control::max_allowed_parallelism,
                        static_cast<std::size_t>(cmd.threads));
  double scene_seconds = 0;
  rockdd::Scene scene;
  {
    rockdd::ScopedTimer timer(scene_seconds);
    scene = rockdd::load_scene(cmd.scene, cmd.overrides);
  }
  rockdd::BuiltModel built = rockdd::build_scene_model_reported(scene);
  built.setup.startup = startup;
  built.setup.scene = scene_seconds;
  rockdd::Simulation sim(scene, std::move(built.model), std::move(built.mesh_slot));
  Progress progress(cmd.quiet);
  rockdd::RunOptions options;
  options.setup = built.setup;
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

/// rockdd mc: tools/monte_carlo_command.cpp.
int monte_carlo(const Command& cmd) {
  rockdd::cli::MonteCarloOptions options;
  options.scene = cmd.scene;
  options.overrides = cmd.overrides;
  options.realizations = cmd.realizations;
  if (cmd.first_seed) options.first_seed = static_cast<std::uint64_t>(*cmd.first_seed);
  options.threads = cmd.threads;
  options.jobs = cmd.jobs;
  if (cmd.out) options.out = *cmd.out;
  options.shard = cmd.shard.value_or(rockdd::Shard{});
  options.restart = cmd.restart;
  options.frames = cmd.frames;
  options.quiet = cmd.quiet;
#ifdef ROCKDD_HAVE_MPI
  // Under mpirun the ranks share the seeds; MPI is initialized only then.
  if (rockdd::cli::launched_by_mpi()) return rockdd::cli::mpi_monte_carlo(options);
#endif
  return rockdd::cli::monte_carlo(options);
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
  // The run's length (step_budget): the steps it asks for at time.dt and their time.
  const double steps = rockdd::scene_steps(scene.time);
  const rockdd::RunTimeEstimate time = rockdd::estimated_run_time(steps, model.num_elements());
  char text[160];
  std::snprintf(text, sizeof text, "%.0f (budget %lld, time.max_steps)", steps,
                static_cast<long long>(scene.time.max_steps));
  std::cout << "\nsteps: " << text
            << (scene.time.stop_at_softening ? ", fewer when the run ends on softening" : "");
  std::snprintf(text, sizeof text, "%.2g to %.2g s", time.fastest, time.slowest);
  std::cout << "\nestimated run time: " << text << " ("
            << rockdd::kFastestStepSecondsPerElement * 1e6 << " to "
            << rockdd::kSlowestStepSecondsPerElement * 1e6
            << " us a step per element, measured on data/'s scenes on 2 threads; dt control, "
               "damage and contact move a run within and beyond it)";
  std::cout << "\ndefaults:\n";
  for (const auto& [key, value] : scene.defaults)
    std::cout << "  " << key << " = " << value << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Before any engine work: what loading the libraries and static initialisation took.
  const std::optional<double> startup = rockdd::process_age_seconds();
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
    // The engine reads the cache folder from the environment; mc's workers inherit it.
    if (cmd.mesh_cache) ::setenv("ROCKDD_MESH_CACHE", cmd.mesh_cache->c_str(), 1);
    if (cmd.verb == "run") return run(cmd, startup);
    if (cmd.verb == "check") return check(cmd);
    if (cmd.verb == "mc-merge")
      return rockdd::cli::monte_carlo_merge(
          cmd.folders.front(), {cmd.folders.begin() + 1, cmd.folders.end()}, cmd.quiet);
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

// rockdd command line: a thin client of the engine library (engine/engine.hpp), its options
// parsed by CLI11 (each command's --help lists its own, with descriptions and defaults).
#include <CLI/CLI.hpp>
#include <oneapi/tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/common/process_clock.hpp"
#include "engine/engine.hpp"
#include "engine/monte_carlo/ensemble_progress.hpp"
#include "engine/output/run_outputs.hpp"
#include "engine/report/run_result.hpp"
#include "engine/scene/step_budget.hpp"
#include "engine/solver/blas_kernels.hpp"
#include "tools/monte_carlo_command.hpp"
#ifdef ROCKDD_HAVE_MPI
#include "tools/mpi_ensemble.hpp"
#endif

namespace {

namespace fs = std::filesystem;

constexpr const char* kExitStatus =
    "Exit status: 0 success, 1 the run failed numerically (the reason is printed and written to "
    "summary.json), 2 bad input (a scene key, a file or an option: the message names it and "
    "what was expected; nothing is written).";

constexpr const char* kCommands =
    "Commands (rockdd COMMAND --help lists each one's options):\n"
    "  run       run a scene: summary.json, history.csv, VTU frames, profiles\n"
    "  check     read and mesh a scene, print its counts, defaults and length; no solve\n"
    "  mc        an ensemble over heterogeneity seeds: mc.csv, mc.json\n"
    "  mc-merge  join the folders of an ensemble's shards\n"
    "  (mpirun -n K rockdd mc ...: K ranks share the seeds, in an MPI build)\n";

/// Where the example scenes (data/) and the documentation (docs/) are: share/rockdd beside the
/// installed binary, else the source tree this binary was built from.
fs::path share_folder() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "rockdd";
    if (fs::is_regular_file(installed / "docs" / "scene.md", error)) return installed;
  }
#ifdef ROCKDD_SOURCE_TREE
  if (fs::is_regular_file(fs::path(ROCKDD_SOURCE_TREE) / "docs" / "scene.md", error))
    return ROCKDD_SOURCE_TREE;
#endif
#ifdef ROCKDD_INSTALL_SHARE
  return ROCKDD_INSTALL_SHARE;
#else
  return {};
#endif
}

std::string general_help() {
  const fs::path share = share_folder();
  std::string text =
      "rockdd " + std::string(rockdd::version()) +
      ": rock fracture from continuum to discontinuum (coupled FEM/DDA)\n\n"
      "usage:\n"
      "  rockdd run SCENE [--out DIR] [--threads N] [--set key.path=value ...] [--quiet]\n"
      "                   [--mesh-cache DIR|off]\n"
      "  rockdd check SCENE [--set key.path=value ...] [--mesh-cache DIR|off]\n"
      "  rockdd mc SCENE --realizations N [--first-seed S] [--threads N] [--jobs J]\n"
      "                  [--out DIR] [--shard I/N] [--restart] [--frames | --no-last-frame]\n"
      "                  [--set key.path=value ...] [--quiet] [--mesh-cache DIR|off]\n"
      "  rockdd mc-merge OUTDIR DIR1 DIR2 ... [--quiet]\n"
      "  rockdd --version | --help\n\n" +
      std::string(kCommands) + "\n";
  if (!share.empty())
    text += "Example scenes: " + (share / "data").string() +
            "\nDocumentation:  " + (share / "docs").string() +
            "\n  the scene file and every output: " + (share / "docs" / "scene.md").string() +
            "\n\n";
  return text + kExitStatus + "\n";
}

/// Bad command line: usage error, exit 2.
struct UsageError {
  std::string message;
};

long parse_integer(const std::string& flag, const std::string& text, long min) {
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < min)
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

/// The options as CLI11 read them (integers as text, checked by parse_integer for messages
/// that name the option and the value).
struct Options {
  std::string scene, out, threads, mesh_cache, realizations, first_seed, jobs, shard;
  std::vector<std::string> overrides, folders;
  bool quiet = false, restart = false, frames = false, no_last_frame = false;
  std::vector<std::string> command;  // argv as given
};

/// Each command and its options, for CLI11.
struct CommandLine {
  CLI::App app{"rockdd: rock fracture from continuum to discontinuum (coupled FEM/DDA)", "rockdd"};
  Options o;
  CLI::App *run = nullptr, *check = nullptr, *mc = nullptr, *merge = nullptr;

  CommandLine() {
    app.require_subcommand(1, 1);
    app.set_help_flag();  // rockdd --help is general_help(), handled before parsing
    app.footer(kExitStatus);
    run = app.add_subcommand("run", "Run a scene to its end (time.end, time.steps or the end on "
                                    "softening): summary.json, history.csv, VTU frames, line "
                                    "profiles in DIR/<scene name>/.");
    check = app.add_subcommand("check", "Read, validate and mesh a scene; print its elements, "
                                        "nodes, blocks, named sets, steps, estimated run time "
                                        "and the defaults chosen. Writes nothing, solves nothing.");
    mc = app.add_subcommand("mc", "Run the scene once per heterogeneity seed (S, S+1, ...), each in "
                                  "a worker process: DIR/<scene name>/seed_<S>/, mc.csv (a row a "
                                  "seed) and mc.json (statistics, Weibull fits). Resumes: the same "
                                  "command again runs only the seeds without a row.");
    merge = app.add_subcommand("mc-merge", "Join the folders DIR1 DIR2 ... of one ensemble's "
                                           "shards into OUTDIR/mc.csv and OUTDIR/mc.json.");
    for (CLI::App* sub : {run, check, mc, merge}) {
      sub->footer(kExitStatus);
      sub->set_help_flag("-h,--help", "Print this help and exit");
    }

    for (CLI::App* sub : {run, check, mc})
      sub->add_option("SCENE", o.scene, "The scene file (TOML; every key: docs/scene.md)")
          ->required()
          ->type_name("FILE");
    for (CLI::App* sub : {run, mc})
      sub->add_option("--out", o.out,
                      "Output root: files go to DIR/<scene name>/ (default: the scene's "
                      "output.dir, \"out\" unless it says otherwise)")
          ->type_name("DIR");
    run->add_option("--threads", o.threads,
                    "Threads for the whole run (default: every hardware thread)")
        ->type_name("N");
    mc->add_option("--threads", o.threads,
                   "Threads in all, shared among the --jobs workers (default: every hardware "
                   "thread)")
        ->type_name("N");
    for (CLI::App* sub : {run, check, mc})
      sub->add_option("--set", o.overrides,
                      "Override a scene key before validation, e.g. --set "
                      "mesh.element_size=2.5e-4, --set material.0.young=30e9, --set "
                      "'boundary.1.velocity=[0,-1e-5]' (repeat for more; default: none)")
          ->type_name("KEY.PATH=VALUE")
          ->expected(1)
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    for (CLI::App* sub : {run, check, mc})
      sub->add_option("--mesh-cache", o.mesh_cache,
                      "Where meshes are kept between runs, or 'off' (default: "
                      "$ROCKDD_MESH_CACHE, else $XDG_CACHE_HOME/rockdd/meshes or "
                      "~/.cache/rockdd/meshes)")
          ->type_name("DIR|off");
    run->add_flag("--quiet", o.quiet, "No progress line and no closing message (default: off)");
    mc->add_flag("--quiet", o.quiet,
                 "No announcement, progress lines or closing message (default: off)");
    merge->add_flag("--quiet", o.quiet, "No closing message (default: off)");

    mc->add_option("--realizations", o.realizations,
                   "Number of seeds (required); a larger N extends an earlier ensemble")
        ->type_name("N")
        ->required();
    mc->add_option("--first-seed", o.first_seed,
                   "The first seed (default: the scene's material seed)")
        ->type_name("S");
    mc->add_option("--jobs", o.jobs,
                   "Realizations at once, each in its own worker process (default: one per "
                   "thread)")
        ->type_name("J");
    mc->add_option("--shard", o.shard,
                   "Run only realizations I, I+N, I+2N, ... (1 <= I <= N), for a cluster job "
                   "array; join the shards with rockdd mc-merge (default: all of them)")
        ->type_name("I/N");
    mc->add_flag("--restart", o.restart,
                 "Discard the rows of an earlier run in the folder (needed when the scene, the "
                 "--set overrides or the first seed changed; default: off, resume)");
    CLI::Option* frames = mc->add_flag(
        "--frames", o.frames,
        "Every realization writes all its VTU frames, as rockdd run does (default: off, only "
        "the last frame)");
    mc->add_flag("--no-last-frame", o.no_last_frame,
                 "Keep no VTU frame at all; without it each realization keeps its last frame "
                 "(compressed unless output.compress = false), the crack pattern that "
                 "tools/plot ensemble --html draws (default: off)")
        ->excludes(frames);
    merge->add_option("FOLDERS", o.folders,
                      "OUTDIR, then the shards' folders DIR1 DIR2 ... (each "
                      "<out>/<scene name>/ of one rockdd mc --shard)")
        ->type_name("OUTDIR DIR1")
        ->required()
        ->expected(2, -1);
  }
};

/// The options `sub` takes, for messages: "--out, --threads, --set, ...".
std::string options_of(const CLI::App& sub) {
  std::string names;
  for (const CLI::Option* option : sub.get_options())
    if (!option->get_lnames().empty() && option->get_lnames().front() != "help")
      names += (names.empty() ? "--" : ", --") + option->get_lnames().front();
  return names;
}

/// What CLI11 left over of `sub`'s arguments, for a message naming it: the options it does
/// not take (a value after one is taken for that option's), else the arguments too many.
std::string refused(const CLI::App& sub, const std::vector<std::string>& extras) {
  std::vector<std::string> options, arguments;
  for (const std::string& extra : extras)
    (extra.size() > 1 && extra[0] == '-' ? options : arguments).push_back(extra);
  const std::string command = "rockdd " + sub.get_name();
  const std::string takes = "; " + sub.get_name() + " takes " + options_of(sub) + " (" + command +
                            " --help)";
  if (!options.empty()) {
    std::string text = command + ": unknown option";
    text += options.size() > 1 ? "s" : "";
    for (std::size_t i = 0; i < options.size(); ++i)
      text += (i ? ", '" : " '") + options[i].substr(0, options[i].find('=')) + "'";
    return text + takes;
  }
  std::string text = command + ": unexpected argument";
  for (std::size_t i = 0; i < arguments.size(); ++i) text += (i ? ", '" : " '") + arguments[i] + "'";
  return text + takes;
}

/// Progress of `rockdd run`: on a terminal one line rewritten in place, elsewhere a line at
/// each tenth of the run and at least every 10 s (progress_interval_seconds). The fraction done is
/// whatever ends the run first: simulated time against time.end, or, once the watched column
/// has fallen from its peak, how far it has fallen against time.stop_at_softening.
class Progress {
 public:
  Progress(bool quiet, const rockdd::Scene& scene)
      : quiet_(quiet),
        tty_(isatty(STDERR_FILENO) != 0),
        softening_column_(scene.time.softening_probe),
        softening_drop_(scene.time.stop_at_softening.value_or(0.0)),
        log_interval_(rockdd::cli::progress_interval_seconds()) {}
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// A history row (RunOutputs::observe_rows): the watched column's peak and fall.
  void row(const std::vector<std::string>& columns, const std::vector<double>& values) {
    if (softening_column_.empty()) return;
    if (column_ < 0)
      for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i] == softening_column_) column_ = static_cast<long>(i);
    if (column_ < 0 || static_cast<std::size_t>(column_) >= values.size()) return;
    const double v = std::abs(values[static_cast<std::size_t>(column_)]);
    peak_ = std::max(peak_, v);
    if (peak_ > 0.0 && softening_drop_ > 0.0) {
      fallen_ = std::clamp((peak_ - v) / peak_, 0.0, 1.0);
      // The bar never goes back when the force rises again after a partial fall.
      softened_ = std::max(softened_, std::min(1.0, fallen_ / softening_drop_));
    }
  }

  /// A committed step.
  void step(const rockdd::StepReport& r) {
    if (quiet_) return;
    const auto now = Clock::now();
    last_report_ = r;
    const double fraction = fraction_done(r);
    if (tty_) {
      if (fraction < 1.0 && seconds(last_, now) < 0.1) return;
      print_line(r, fraction, now);
    } else {
      const int decile = static_cast<int>(std::floor(fraction * 10 + 1e-9));
      if (decile <= last_decile_ && seconds(last_, now) < log_interval_) return;
      last_decile_ = std::max(last_decile_, decile);
      print_line(r, fraction, now);
    }
  }

  /// Ends the progress output: the run's last state, and a newline on a terminal, so that
  /// the next message starts a line of its own. `fell_apart`: the run ended before its end
  /// because its specimen fell apart (summary.json disintegration): nothing is left to do.
  void finish(bool fell_apart = false) {
    if (quiet_ || finished_) return;
    finished_ = true;
    if (fell_apart && last_report_) {
      ended_ = "  ended: fell apart";
      print_line(*last_report_, 1.0, Clock::now());
    } else if (last_report_ && last_printed_step_ != last_report_->step) {
      print_line(*last_report_, fraction_done(*last_report_), Clock::now());
    }
    if (tty_ && line_open_) std::fputc('\n', stderr);
    line_open_ = false;
    std::fflush(stderr);
  }

 private:
  using Clock = std::chrono::steady_clock;

  static double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  }

  double fraction_done(const rockdd::StepReport& r) const {
    const double by_time = r.end_time > 0 ? std::clamp(r.time / r.end_time, 0.0, 1.0) : 1.0;
    return std::max(by_time, softened_);
  }

  void print_line(const rockdd::StepReport& r, double fraction, Clock::time_point now) {
    last_ = now;
    last_printed_step_ = r.step;
    const double elapsed = seconds(start_, now);
    const double rate = r.step / std::max(elapsed, 1e-9);
    const std::string eta = fraction >= 1.0 ? "00:00:00"
                            : fraction > 0  ? rockdd::clock_time(elapsed * (1 - fraction) / fraction)
                                            : "--";
    char what[96] = "";
    if (!ended_.empty())
      std::snprintf(what, sizeof what, "%s", ended_.c_str());
    else if (softened_ > 0.0 && softened_ >= r.time / std::max(r.end_time, 1e-300))
      std::snprintf(what, sizeof what, "  softened %.0f%% of %.0f%%", 100 * fallen_,
                    100 * softening_drop_);
    if (tty_) {
      const int width = 30, filled = static_cast<int>(std::lround(fraction * width));
      std::fprintf(stderr,
                   "\r[%.*s%*s] %5.1f%%  t = %.4g s  step %ld  %.0f steps/s  ETA %s%s\033[K",
                   filled, "##############################", width - filled, "", 100 * fraction,
                   r.time, r.step, rate, eta.c_str(), what);
      line_open_ = true;
    } else {
      std::fprintf(stderr,
                   "rockdd: step %ld  t = %.6g s  %.1f%% done%s  %.2f s elapsed  %.1f steps/s  "
                   "ETA %s\n",
                   r.step, r.time, 100 * fraction, what, elapsed, rate, eta.c_str());
    }
    std::fflush(stderr);
  }

  const bool quiet_, tty_;
  const std::string softening_column_;
  const double softening_drop_;
  const double log_interval_;  // s between two lines off a terminal, at the most
  long column_ = -1;
  double peak_ = 0.0;
  double fallen_ = 0.0;    // the watched column's fall below its peak now, a fraction of it
  std::string ended_;  // why the run ended before its end time, for the last line
  double softened_ = 0.0;  // the most of the fall that ends the run seen so far, in [0, 1]
  int last_decile_ = -1;
  bool line_open_ = false, finished_ = false;
  long last_printed_step_ = -1;
  std::optional<rockdd::StepReport> last_report_;
  Clock::time_point start_ = Clock::now(), last_ = Clock::now();
};

int run(const Options& o, std::optional<double> startup) {
  const int threads = o.threads.empty() ? 0 : static_cast<int>(parse_integer("--threads", o.threads, 1));
  // --threads bounds the whole run: the model and the simulation's set-up too, not only its
  // steps (RunOptions::threads).
  std::optional<tbb::global_control> parallelism;
  if (threads > 0)
    parallelism.emplace(tbb::global_control::max_allowed_parallelism,
                        static_cast<std::size_t>(threads));
  double scene_seconds = 0;
  rockdd::Scene scene;
  {
    rockdd::ScopedTimer timer(scene_seconds);
    scene = rockdd::load_scene(o.scene, o.overrides);
  }
  rockdd::BuiltModel built = rockdd::build_scene_model_reported(scene);
  built.setup.startup = startup;
  built.setup.scene = scene_seconds;
  rockdd::Simulation sim(scene, std::move(built.model), std::move(built.mesh_slot));
  Progress progress(o.quiet, scene);
  rockdd::RunOptions options;
  options.setup = built.setup;
  if (!o.out.empty()) options.out_root = o.out;
  options.threads = threads;
  options.on_step = [&](const rockdd::StepReport& r, const rockdd::Model&) { progress.step(r); };
  rockdd::RunOutputs::observe_rows(
      [&](long, const std::vector<std::string>& columns, const std::vector<double>& values) {
        progress.row(columns, values);
      });
  const rockdd::RunResult result = sim.run(options);
  rockdd::RunOutputs::observe_rows({});
  progress.finish(result.summary.contains("disintegration"));
  const auto out_dir =
      (options.out_root.empty() ? scene.output.dir : options.out_root) / scene.name;
  // A balance that does not close is said even when quiet: the answer may be wrong.
  if (const auto& check = result.summary["energy_check"]; check.contains("warning"))
    std::cerr << "rockdd: warning: " << check["warning"].get<std::string>()
              << " (summary.json energy, energy_check)\n";
  if (!result.ok) {
    std::cerr << "rockdd: run failed: " << result.reason << "\n  outputs so far in "
              << out_dir.string() << "\n";
    return 1;
  }
  if (!o.quiet) {
    std::cerr << "rockdd: ok: " << result.summary["steps"] << " steps, "
              << result.summary["elements"] << " elements, " << result.summary["blocks"]
              << " blocks, " << result.summary["wall_seconds"].get<double>() << " s";
    if (result.summary.contains("softening") && result.summary["softening"]["reached"] == true)
      std::cerr << ", ended on softening at t = " << result.summary["softening"]["time"] << " s";
    if (result.summary.contains("disintegration")) {
      const auto& d = result.summary["disintegration"];
      std::cerr << ", ended at step " << d["step"] << " (t = " << d["time"].get<double>()
                << " s): ";
      if (d["cause"] == "fragments")
        std::cerr << "fracture left the specimen in " << d["blocks"]
                  << " loose fragments, the largest "
                  << 100 * d["largest_block_share"].get<double>() << " % of it";
      else
        std::cerr << "no chain of rock and closed contacts joins the moving boundary to a held "
                     "one any more (the largest of "
                  << d["blocks"] << " blocks holds " << 100 * d["largest_block_share"].get<double>()
                  << " % of the specimen)";
      std::cerr << ", so nothing of it carries load (analysis = \"dynamic\" follows fragments)";
    }
    std::cerr << "; outputs in " << out_dir.string() << "\n";
  }
  return 0;
}

/// rockdd mc: tools/monte_carlo_command.cpp.
int monte_carlo(const Options& o) {
  rockdd::cli::MonteCarloOptions options;
  options.scene = o.scene;
  options.overrides = o.overrides;
  options.realizations = parse_integer("--realizations", o.realizations, 1);
  if (!o.first_seed.empty())
    options.first_seed = static_cast<std::uint64_t>(parse_integer("--first-seed", o.first_seed, 0));
  if (!o.threads.empty()) options.threads = static_cast<int>(parse_integer("--threads", o.threads, 1));
  if (!o.jobs.empty()) options.jobs = static_cast<int>(parse_integer("--jobs", o.jobs, 1));
  if (!o.out.empty()) options.out = o.out;
  if (!o.shard.empty()) options.shard = parse_shard(o.shard);
  options.restart = o.restart;
  options.frames = o.frames;
  options.last_frame = !o.no_last_frame;
  options.quiet = o.quiet;
  options.command = o.command;
#ifdef ROCKDD_HAVE_MPI
  // Under mpirun the ranks share the seeds; MPI is initialized only then.
  if (rockdd::cli::launched_by_mpi()) return rockdd::cli::mpi_monte_carlo(options);
#endif
  return rockdd::cli::monte_carlo(options);
}

int check(const Options& o) {
  const rockdd::Scene scene = rockdd::load_scene(o.scene, o.overrides);
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

/// CLI11's help with long lines wrapped at 100 columns: an option's description continues
/// under its own column, other text flush left.
std::string wrapped(const std::string& help) {
  constexpr std::size_t kWidth = 100, kColumn = 30;
  std::string out;
  std::size_t start = 0;
  while (start < help.size()) {
    std::size_t end = help.find('\n', start);
    if (end == std::string::npos) end = help.size();
    std::string line = help.substr(start, end - start);
    start = end + 1;
    const bool option = line.rfind("  ", 0) == 0 && line.size() > kColumn &&
                        line[kColumn - 1] == ' ' && line[kColumn] != ' ';
    const std::string indent(option ? kColumn : 0, ' ');
    while (line.size() > kWidth) {
      std::size_t cut = line.rfind(' ', kWidth);
      if (cut == std::string::npos || cut <= indent.size()) break;
      out += line.substr(0, cut) + '\n';
      line = indent + line.substr(cut + 1);
    }
    out += line + '\n';
  }
  return out;
}

bool is_help(const char* arg) {
  return std::strcmp(arg, "--help") == 0 || std::strcmp(arg, "-h") == 0;
}

}  // namespace

int main(int argc, char** argv) {
  rockdd::restart_with_better_blas_kernels(argv);
  // Before any engine work: what loading the libraries and static initialisation took.
  const std::optional<double> startup = rockdd::process_age_seconds();
  if (argc >= 2 && is_help(argv[1])) {
    std::cout << general_help();
    return 0;
  }
  if (argc >= 2 && std::strcmp(argv[1], "--version") == 0) {
    std::cout << "rockdd " << rockdd::version() << '\n';
    return 0;
  }
  CommandLine line;
  try {
    if (argc < 2) throw UsageError{"missing command"};
    const std::string verb = argv[1];
    if (verb != "run" && verb != "check" && verb != "mc" && verb != "mc-merge")
      throw UsageError{"unknown command '" + verb + "' (the commands are run, check, mc and "
                       "mc-merge)"};
    CLI::App* sub = line.app.get_subcommand(verb);
    line.o.command.assign(argv, argv + argc);
    try {
      line.app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
      std::cout << wrapped(sub->help("rockdd"));
      return 0;
    } catch (const CLI::ExtrasError&) {
      throw UsageError{refused(*sub, sub->remaining())};
    } catch (const CLI::ParseError& e) {
      throw UsageError{"rockdd " + verb + ": " + e.what() + " (rockdd " + verb + " --help)"};
    }
    const Options& o = line.o;
    // The engine reads the cache folder from the environment; mc's workers inherit it.
    if (!o.mesh_cache.empty()) ::setenv("ROCKDD_MESH_CACHE", o.mesh_cache.c_str(), 1);
    try {
      if (verb == "run") return run(o, startup);
      if (verb == "check") return check(o);
      if (verb == "mc-merge")
        return rockdd::cli::monte_carlo_merge(o.folders.front(),
                                              {o.folders.begin() + 1, o.folders.end()}, o.quiet);
      return monte_carlo(o);
    } catch (const UsageError& e) {  // an option's value: name the command
      throw UsageError{"rockdd " + verb + ": " + e.message + " (rockdd " + verb + " --help)"};
    }
  } catch (const UsageError& e) {
    std::cerr << (e.message.rfind("rockdd ", 0) == 0 ? "" : "rockdd: ") << e.message
              << (e.message.find("--help") == std::string::npos ? " (rockdd --help)" : "") << '\n';
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

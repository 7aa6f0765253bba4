// rockdd mc as an ensemble that loses nothing: rows appended as realizations finish, resume,
// a killed parent or worker, shards and their merge, and the statistics of mc.json.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "engine/monte_carlo/ensemble_progress.hpp"
#include "engine/monte_carlo/ensemble_resume.hpp"
#include "engine/monte_carlo/ensemble_statistics.hpp"
#include "engine/monte_carlo/ensemble_table.hpp"
#include "engine/monte_carlo/monte_carlo.hpp"
#include "engine/monte_carlo/weibull_fit.hpp"
#include "support/command_line.hpp"
#include "support/file_text.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

using test::rockdd_cli;

const std::filesystem::path kSource = ROCKDD_SOURCE_DIR;

// ---------------------------------------------------------------------------------------------
// The pieces, without running the engine.

TEST(WeibullFit, RecoversShapeAndScaleOfSyntheticDraws) {
  std::mt19937_64 generator(20240611);
  std::weibull_distribution<double> weibull(5.0, 10.0);
  std::vector<double> x(2000);
  for (double& v : x) v = weibull(generator);
  const auto fit = fit_weibull(x);
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->shape, 5.0, 0.5);   // 10 %
  EXPECT_NEAR(fit->scale, 10.0, 0.2);  // 2 %
  EXPECT_LT(fit->shape_low, fit->shape);
  EXPECT_GT(fit->shape_high, fit->shape);
  EXPECT_LT(fit->scale_low, fit->scale);
  EXPECT_GT(fit->scale_high, fit->scale);
  // With 2000 draws the standard error of m is about 0.78 m / sqrt(n) = 0.087: the 90 %
  // interval is about +-0.14 wide.
  EXPECT_NEAR(fit->shape_high - fit->shape_low, 2 * 1.645 * 0.78 * 5.0 / std::sqrt(2000.0), 0.05);
}

TEST(WeibullFit, SatisfiesTheLikelihoodEquationsAndScalesWithTheData) {
  const std::vector<double> x = {7.1, 8.4, 9.0, 9.3, 10.2, 10.9, 11.5, 12.8};
  const auto fit = fit_weibull(x);
  ASSERT_TRUE(fit);
  // d ln L / d m = 0 and d ln L / d scale = 0 at the optimum.
  double sum_z = 0.0, sum_zl = 0.0, sum_l = 0.0;
  for (const double v : x) {
    const double l = std::log(v / fit->scale), z = std::pow(v / fit->scale, fit->shape);
    sum_z += z;
    sum_zl += z * l;
    sum_l += l;
  }
  const double n = static_cast<double>(x.size());
  EXPECT_NEAR(sum_z, n, 1e-9 * n);
  EXPECT_NEAR(n / fit->shape + sum_l - sum_zl, 0.0, 1e-9 * n);
  std::vector<double> scaled = x;
  for (double& v : scaled) v *= 1e6;
  const auto fit_scaled = fit_weibull(scaled);
  ASSERT_TRUE(fit_scaled);
  EXPECT_NEAR(fit_scaled->shape, fit->shape, 1e-9 * fit->shape);
  EXPECT_NEAR(fit_scaled->scale, 1e6 * fit->scale, 1e-9 * 1e6 * fit->scale);
}

TEST(WeibullFit, NoFitWithoutTwoDistinctPositiveValues) {
  EXPECT_FALSE(fit_weibull(std::vector<double>{}));
  EXPECT_FALSE(fit_weibull(std::vector<double>{3.0}));
  EXPECT_FALSE(fit_weibull(std::vector<double>{3.0, 3.0, 3.0}));
  EXPECT_FALSE(fit_weibull(std::vector<double>{3.0, -1.0}));
  EXPECT_FALSE(fit_weibull(std::vector<double>{3.0, 0.0}));
}

TEST(EnsembleStatistics, QuantilesInterpolateBetweenOrderStatistics) {
  const std::vector<double> x = {1.0, 2.0, 3.0, 4.0, 5.0};
  EXPECT_DOUBLE_EQ(quantile_of_sorted(x, 0.05), 1.2);
  EXPECT_DOUBLE_EQ(quantile_of_sorted(x, 0.50), 3.0);
  EXPECT_DOUBLE_EQ(quantile_of_sorted(x, 0.95), 4.8);
  EXPECT_DOUBLE_EQ(quantile_of_sorted(x, 1.0), 5.0);
  EXPECT_DOUBLE_EQ(quantile_of_sorted(std::vector<double>{7.0}, 0.05), 7.0);
}

TEST(EnsembleStatistics, OnlyOkRowsCountAndStrengthColumnsGetAWeibullFit) {
  const std::vector<std::string> columns = {"peaks.top.fy", "peaks.top.uy", "steps"};
  const std::vector<EnsembleRow> rows = {{1, "ok", {"10", "1e-5", "100"}, ""},
                                         {2, "ok", {"12", "2e-5", "120"}, ""},
                                         {3, "failed", {"99", "9e-5", "5"}, "diverged"},
                                         {4, "crashed", {"", "", ""}, "killed"},
                                         {5, "ok", {"11", "", "110"}, ""}};
  const nlohmann::json s = ensemble_statistics(columns, rows);
  EXPECT_EQ(s["peaks.top.fy"]["count"], 3);
  EXPECT_DOUBLE_EQ(s["peaks.top.fy"]["mean"].get<double>(), 11.0);
  EXPECT_DOUBLE_EQ(s["peaks.top.fy"]["std"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(s["peaks.top.fy"]["q50"].get<double>(), 11.0);
  EXPECT_EQ(s["peaks.top.uy"]["count"], 2);  // an empty cell is no number
  for (const char* key : {"count", "mean", "std", "min", "max", "q05", "q50", "q95"})
    EXPECT_TRUE(s["steps"].contains(key)) << key;
  EXPECT_TRUE(s["peaks.top.fy"].contains("weibull"));
  EXPECT_FALSE(s["peaks.top.uy"].contains("weibull"));  // a displacement, not a strength
  EXPECT_FALSE(s["steps"].contains("weibull"));
  EXPECT_TRUE(is_strength_column("softening.peak"));
  EXPECT_TRUE(is_strength_column("peaks.left.fx"));
  EXPECT_FALSE(is_strength_column("softening.peak_time"));
}

TEST(EnsembleTable, RowsRoundTripWithCommasQuotesAndLineBreaksInTheReason) {
  test::TempDir tmp;
  const auto file = tmp.path() / "mc.csv";
  const std::vector<std::string> columns = {"a", "b,c"};
  {
    EnsembleTableAppender table(file, columns);
    table.append({3, "ok", {"1.5", "2"}, ""});
    table.append({4, "crashed", {"", ""}, "worker said \"no\", then\nstopped"});
  }
  const std::string text = test::read_text(file);
  EXPECT_EQ(text.substr(0, text.find('\n')), "seed,status,a,\"b,c\",reason");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);  // one line per row
  const EnsembleTable read = read_ensemble_table(file);
  EXPECT_EQ(read.columns, columns);
  ASSERT_EQ(read.rows.size(), 2u);
  EXPECT_EQ(read.rows[0].cells, (std::vector<std::string>{"1.5", "2"}));
  EXPECT_EQ(read.rows[1].status, "crashed");
  EXPECT_EQ(read.rows[1].reason, "worker said \"no\", then stopped");
}

TEST(EnsembleTable, ALineCutShortIsLeftOutAndCutOffBeforeTheNextRow) {
  test::TempDir tmp;
  const auto file = tmp.path() / "mc.csv";
  std::ofstream(file) << "seed,status,a,reason\n1,ok,2,\n2,ok,3";  // no newline: cut short
  EXPECT_EQ(read_ensemble_table(file).rows.size(), 1u);
  {
    EnsembleTableAppender table(file, {"a"});
    table.append({2, "ok", {"3"}, ""});
  }
  EXPECT_EQ(test::read_text(file), "seed,status,a,reason\n1,ok,2,\n2,ok,3,\n");
}

TEST(EnsembleTable, TheLastRowOfASeedCountsAndCrashedSeedsRunAgain) {
  const std::vector<EnsembleRow> rows = {{5, "crashed", {}, "killed"},
                                         {2, "ok", {}, ""},
                                         {3, "failed", {}, "diverged"},
                                         {5, "ok", {}, ""},
                                         {6, "crashed", {}, "killed"}};
  const auto latest = latest_rows(rows);
  ASSERT_EQ(latest.size(), 4u);
  EXPECT_EQ(latest[2].seed, 5u);
  EXPECT_EQ(latest[2].status, "ok");
  EXPECT_EQ(seeds_to_run({1, 2, 3, 4, 5, 6}, rows), (std::vector<std::uint64_t>{1, 4, 6}));
}

TEST(EnsembleProgress, LineGivesCountsRateAndEta) {
  EnsembleProgress p;
  p.total = 8;
  p.done = 5;
  p.running = 2;
  p.failed = 1;
  p.finished_here = 5;
  p.elapsed_s = 50.0;  // 360 realizations/h
  p.slots = 2;
  p.mean_realization_s = 20.0;
  p.running_for = {15.0, 5.0};  // 5 s and 15 s left; the last one starts in the first slot
  EXPECT_EQ(progress_line(p),
            "mc: 5/8 done, 2 running, 1 failed, 360 realizations/h, ETA 00:00:25");
  EXPECT_EQ(clock_time(3 * 3600 + 61), "03:01:01");
  p.finished_here = 0;
  EXPECT_EQ(progress_line(p), "mc: 5/8 done, 2 running, 1 failed, -- realizations/h, ETA --");
}

TEST(EnsembleProgress, EtaOverlapsTheJobsAndCountsWhatTheRunningOnesHaveDone) {
  // Issue 31: "ETA 00:00:31" about 4 s before the end: the ETA was the realizations left over
  // the ensemble's rate, blind to the running ones being nearly done.
  EnsembleProgress p;
  p.total = 4;
  p.done = 2;
  p.running = 2;
  p.finished_here = 2;
  p.elapsed_s = 30.0;
  p.slots = 2;
  p.mean_realization_s = 15.0;
  p.running_for = {11.0, 11.0};  // both end in about 4 s
  EXPECT_DOUBLE_EQ(ensemble_eta_seconds(p), 4.0);
  // Six to go on two slots, none running: three rounds of 10 s.
  p = {};
  p.total = 6;
  p.finished_here = 1;
  p.done = 0;
  p.slots = 2;
  p.mean_realization_s = 10.0;
  EXPECT_DOUBLE_EQ(ensemble_eta_seconds(p), 30.0);
  // One slot: one after the other.
  p.slots = 1;
  EXPECT_DOUBLE_EQ(ensemble_eta_seconds(p), 60.0);
  // A running realization past the mean is expected to end now, not to have negative time.
  p = {};
  p.total = 3;
  p.done = 2;
  p.running = 1;
  p.finished_here = 2;
  p.slots = 2;
  p.mean_realization_s = 10.0;
  p.running_for = {14.0};
  EXPECT_DOUBLE_EQ(ensemble_eta_seconds(p), 0.0);
  // Running seeds whose start is not known here (MPI peers): half a realization each.
  p.running_for = {};
  EXPECT_DOUBLE_EQ(ensemble_eta_seconds(p), 5.0);
  // Nothing finished yet: unknown; everything done: none left.
  p.finished_here = 0;
  EXPECT_LT(ensemble_eta_seconds(p), 0.0);
  p.done = p.total;
  EXPECT_DOUBLE_EQ(ensemble_eta_seconds(p), 0.0);
}

TEST(MonteCarloPlan, ShardsSplitTheRealizationsRoundRobin) {
  MonteCarloPlan plan;
  plan.first_seed = 10;
  plan.realizations = 5;
  EXPECT_EQ(plan.seeds(), (std::vector<std::uint64_t>{10, 11, 12, 13, 14}));
  plan.shard = {1, 2};
  EXPECT_EQ(plan.seeds(), (std::vector<std::uint64_t>{10, 12, 14}));
  plan.shard = {2, 2};
  EXPECT_EQ(plan.seeds(), (std::vector<std::uint64_t>{11, 13}));
}

// ---------------------------------------------------------------------------------------------
// The command line on the uniaxial compression specimen, coarse (400 elements, about 2 s a
// realization).

const std::string kScene = "'" + (kSource / "data/uniaxial_compression.toml").string() + "'";
const std::string kCoarse = " --set 'mesh.divisions=[10, 20]'";
const std::string kFolder = "uniaxial-compression";

/// mc.csv's lines (header first).
std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::stringstream in(test::read_text(file));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// mc.csv's rows without their wall time (which no two runs share), as text.
std::vector<std::string> rows_without_wall_time(const std::filesystem::path& file) {
  const std::vector<std::string> lines = lines_of(file);
  std::vector<std::string> header;
  std::stringstream h(lines.at(0));
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const auto wall = std::find(header.begin(), header.end(), "wall_seconds") - header.begin();
  std::vector<std::string> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::stringstream r(lines[i]);
    std::string row;
    long c = 0;
    for (std::string cell; std::getline(r, cell, ','); ++c)
      if (c != wall) row += cell + ",";
    rows.push_back(row);
  }
  return rows;
}

std::size_t cells_in(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

/// `rockdd ARGS` started in the background in `cwd` (output into `log`); its process id.
pid_t start_rockdd(const std::string& args, const std::filesystem::path& cwd,
                   const std::filesystem::path& log) {
  const std::string command = "cd '" + cwd.string() + "' && exec '" + ROCKDD_BINARY + "' " + args +
                              " >'" + log.string() + "' 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

/// Waits (up to `timeout_s`) until `condition` holds; false when it never did.
template <class Condition>
bool poll_until(Condition condition, double timeout_s = 120.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!condition()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

/// The children of process `parent` (from /proc).
std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string text;
    std::getline(stat, text);
    const std::size_t close = text.rfind(')');
    if (close == std::string::npos) continue;
    std::stringstream rest(text.substr(close + 2));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid == parent && state != 'Z') out.push_back(std::stoi(name));
  }
  return out;
}

/// The name a process gave itself (PR_SET_NAME), empty once it has gone.
std::string name_of(pid_t pid) {
  std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
  std::string name;
  std::getline(comm, name);
  return name;
}

/// True while process `pid` runs (a zombie has ended).
bool running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return false;
  const std::size_t close = text.rfind(')');
  return close != std::string::npos && close + 2 < text.size() && text[close + 2] != 'Z';
}

std::filesystem::file_time_type modified(const std::filesystem::path& file) {
  return std::filesystem::last_write_time(file);
}

#ifdef ROCKDD_MPIEXEC
/// `mpirun --oversubscribe -n RANKS rockdd ARGS` in `cwd` (as root too), stopped after 300 s.
test::Invocation mpi_rockdd_cli(int ranks, const std::string& args,
                                const std::filesystem::path& cwd) {
  const std::string command = "cd '" + cwd.string() +
                              "' && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                              "timeout -k 5 300 '" ROCKDD_MPIEXEC "' --oversubscribe -n " +
                              std::to_string(ranks) + " '" + ROCKDD_BINARY + "' " + args + " 2>&1";
  return test::run_shell(command);
}
#endif

TEST(MonteCarloCommand, RowsDoNotDependOnJobsShardsOrMpiRanks) {
  // Eight seeds one at a time, two at a time, as two shards merged and on two MPI ranks (an
  // MPI build): the same rows, bitwise in every column but wall time.
  test::TempDir tmp;
  const std::string mc = "mc " + kScene + " --realizations 8 --first-seed 7 --threads 2" + kCoarse;
  const auto one = rockdd_cli(mc + " --jobs 1 --out one", tmp.path());
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto two = rockdd_cli(mc + " --jobs 2 --out two", tmp.path());
  ASSERT_EQ(two.exit_code, 0) << two.output;
  for (const char* shard : {"1/2", "2/2"}) {
    const auto part = rockdd_cli(
        mc + " --jobs 1 --shard " + shard + " --out shard" + std::string(1, shard[0]), tmp.path());
    ASSERT_EQ(part.exit_code, 0) << part.output;
  }
  // A shard folder holds only its own seeds.
  EXPECT_EQ(rows_without_wall_time(tmp.path() / "shard1" / kFolder / "mc.csv").size(), 4u);
  const auto merge =
      rockdd_cli("mc-merge merged shard1/" + kFolder + " shard2/" + kFolder, tmp.path());
  ASSERT_EQ(merge.exit_code, 0) << merge.output;

  const auto rows = rows_without_wall_time(tmp.path() / "one" / kFolder / "mc.csv");
  ASSERT_EQ(rows.size(), 8u);
  for (std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(rows[i].substr(0, rows[i].find(',')), std::to_string(7 + i)) << rows[i];
  EXPECT_NE(rows[0].find(",ok,"), std::string::npos) << rows[0];
  EXPECT_EQ(rows_without_wall_time(tmp.path() / "two" / kFolder / "mc.csv"), rows);
  EXPECT_EQ(rows_without_wall_time(tmp.path() / "merged" / "mc.csv"), rows);
#ifdef ROCKDD_MPIEXEC
  // Rank 0 writes every row, its own and rank 1's, into one mc.csv.
  const auto mpi = mpi_rockdd_cli(2, mc + " --out mpi", tmp.path());
  ASSERT_EQ(mpi.exit_code, 0) << mpi.output;
  EXPECT_NE(mpi.output.find("in each of 2 MPI ranks"), std::string::npos) << mpi.output;
  EXPECT_EQ(rows_without_wall_time(tmp.path() / "mpi" / kFolder / "mc.csv"), rows);
  EXPECT_EQ(nlohmann::json::parse(test::read_text(tmp.path() / "mpi" / kFolder / "mc.json"))["ok"],
            8);
#else
  std::cout << "no MPI build: the mpirun case is not run\n";
#endif

  // mc.json: the same statistics whichever way the rows came, with quantiles and a Weibull
  // fit of the peak strength; the keys of earlier versions are still there.
  const auto report =
      nlohmann::json::parse(test::read_text(tmp.path() / "one" / kFolder / "mc.json"));
  const auto merged = nlohmann::json::parse(test::read_text(tmp.path() / "merged" / "mc.json"));
  for (const char* key :
       {"scene", "realizations", "first_seed", "ok", "failed", "crashed", "hash", "statistics"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["realizations"], 8);
  EXPECT_EQ(report["ok"], 8);
  EXPECT_EQ(report["hash"], merged["hash"]);
  const auto& peak = report["statistics"]["peaks.top.fy"];
  for (const char* key : {"count", "mean", "std", "min", "max", "q05", "q50", "q95", "weibull"})
    EXPECT_TRUE(peak.contains(key)) << key;
  for (const char* key : {"shape", "scale", "shape_ci90", "scale_ci90", "method"})
    EXPECT_TRUE(peak["weibull"].contains(key)) << key;
  EXPECT_LE(peak["q05"].get<double>(), peak["q50"].get<double>());
  EXPECT_LE(peak["q50"].get<double>(), peak["q95"].get<double>());
  EXPECT_TRUE(report["statistics"]["softening.peak"].contains("weibull"));
  EXPECT_EQ(merged["statistics"]["peaks.top.fy"], peak);

  // Without --frames, each realization keeps its last VTU frame only, compressed (issue 31),
  // with its history and summary.
  const auto seed7 = tmp.path() / "one" / kFolder / "seed_7";
  EXPECT_TRUE(std::filesystem::exists(seed7 / "summary.json"));
  EXPECT_TRUE(std::filesystem::exists(seed7 / "history.csv"));
  const long steps = nlohmann::json::parse(test::read_text(seed7 / "summary.json"))["steps"];
  char last[32];
  std::snprintf(last, sizeof last, "frame_%05ld.vtu", steps);
  std::vector<std::string> frames;
  for (const auto& entry : std::filesystem::directory_iterator(seed7 / "frames"))
    frames.push_back(entry.path().filename().string());
  EXPECT_EQ(frames, std::vector<std::string>{last});
  EXPECT_NE(test::read_text(seed7 / "frames" / last).find("compressor=\"vtkZLibDataCompressor\""),
            std::string::npos);
  EXPECT_NE(test::read_text(seed7 / "frames.pvd").find(std::string("frames/") + last),
            std::string::npos);
  // (CommandLine.MonteCarloRunsOneRealizationPerSeedAndTabulatesThem: it is `rockdd run`'s.)
  // Progress lines as realizations finish.
  EXPECT_NE(one.output.find("mc: 8/8 done, 0 running, 0 failed, "), std::string::npos)
      << one.output;
  EXPECT_NE(one.output.find("realizations/h, ETA 00:00:00"), std::string::npos) << one.output;
}

TEST(MonteCarloCommand, MergeRefusesShardsOfAnotherEnsembleOrWithTheSameSeeds) {
  test::TempDir tmp;
  const std::string mc = "mc " + kScene + " --realizations 2 --first-seed 7 --threads 2" + kCoarse +
                         " --shard 1/2 --quiet";
  ASSERT_EQ(rockdd_cli(mc + " --out a", tmp.path()).exit_code, 0);
  const auto a = tmp.path() / "a" / kFolder;
  const auto same = rockdd_cli("mc-merge m1 a a", tmp.path());  // seed 7 twice
  EXPECT_EQ(same.exit_code, 2) << same.output;
  EXPECT_NE(same.output.find("seed 7"), std::string::npos) << same.output;
  // Another ensemble: the same rows under a manifest of another first seed.
  std::filesystem::copy(a, tmp.path() / "b", std::filesystem::copy_options::recursive);
  auto manifest = nlohmann::json::parse(test::read_text(tmp.path() / "b/mc.manifest.json"));
  manifest["first_seed"] = 8;
  std::ofstream(tmp.path() / "b/mc.manifest.json") << manifest.dump();
  std::ofstream(tmp.path() / "b/mc.csv") << lines_of(a / "mc.csv").at(0) << "\n";
  const auto other = rockdd_cli("mc-merge m2 a b", tmp.path());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("first seed"), std::string::npos) << other.output;
  EXPECT_NE(other.output.find("mc.manifest.json"), std::string::npos) << other.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "m2" / "mc.csv"));
  // An --out root with one scene folder names that folder.
  const auto root = rockdd_cli("mc-merge m3 a", tmp.path());
  EXPECT_EQ(root.exit_code, 0) << root.output;
  EXPECT_EQ(lines_of(tmp.path() / "m3" / "mc.csv"), lines_of(a / "mc.csv"));
}

TEST(MonteCarloCommand, ResumeRunsOnlyTheNewSeedsAndRefusesAnotherEnsemble) {
  test::TempDir tmp;
  const std::string mc = "mc " + kScene + " --first-seed 7 --threads 2 --jobs 1 --out mc" + kCoarse;
  const auto dir = tmp.path() / "mc" / kFolder;
  ASSERT_EQ(rockdd_cli(mc + " --realizations 2", tmp.path()).exit_code, 0);
  const std::vector<std::string> first = lines_of(dir / "mc.csv");
  ASSERT_EQ(first.size(), 3u);
  const auto t7 = modified(dir / "seed_7/summary.json");
  const auto t8 = modified(dir / "seed_8/summary.json");

  const auto more = rockdd_cli(mc + " --realizations 4", tmp.path());
  ASSERT_EQ(more.exit_code, 0) << more.output;
  EXPECT_NE(more.output.find("2 already in"), std::string::npos) << more.output;
  EXPECT_NE(more.output.find("2 to run"), std::string::npos) << more.output;
  EXPECT_EQ(more.output.find("mc: seed 7:"), std::string::npos) << more.output;
  EXPECT_NE(more.output.find("mc: seed 10: ok"), std::string::npos) << more.output;
  const std::vector<std::string> all = lines_of(dir / "mc.csv");
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(std::vector<std::string>(all.begin(), all.begin() + 3), first);  // byte for byte
  EXPECT_EQ(modified(dir / "seed_7/summary.json"), t7);
  EXPECT_EQ(modified(dir / "seed_8/summary.json"), t8);
  EXPECT_EQ(nlohmann::json::parse(test::read_text(dir / "mc.json"))["realizations"], 4);

  // The same command again runs nothing.
  const auto again = rockdd_cli(mc + " --realizations 4", tmp.path());
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("0 to run"), std::string::npos) << again.output;

  // Another --set, or another first seed: refused, naming the manifest and --restart.
  const std::string changed = " --set time.stop_at_softening=0.5";
  const auto refused = rockdd_cli(mc + " --realizations 4" + changed, tmp.path());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--restart"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("mc.manifest.json"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("--set overrides"), std::string::npos) << refused.output;
  const auto seed = rockdd_cli(
      "mc " + kScene + " --first-seed 8 --threads 2 --out mc" + kCoarse + " --realizations 1",
      tmp.path());
  EXPECT_EQ(seed.exit_code, 2) << seed.output;
  EXPECT_NE(seed.output.find("--restart"), std::string::npos) << seed.output;
  EXPECT_EQ(lines_of(dir / "mc.csv"), all);  // nothing touched

  const auto restart = rockdd_cli(mc + " --realizations 1 --restart" + changed, tmp.path());
  ASSERT_EQ(restart.exit_code, 0) << restart.output;
  const std::vector<std::string> fresh = lines_of(dir / "mc.csv");
  ASSERT_EQ(fresh.size(), 2u);
  EXPECT_EQ(fresh[1].substr(0, 5), "7,ok,");
  EXPECT_NE(fresh[1], all[1]);  // run again, under the new setting
}

TEST(MonteCarloCommand, AKilledParentLeavesWholeRowsAndTheRerunKeepsThem) {
  test::TempDir tmp;
  const std::string mc =
      "mc " + kScene + " --realizations 4 --first-seed 7 --threads 2 --jobs 1 --out mc" + kCoarse;
  const auto dir = tmp.path() / "mc" / kFolder;
  const pid_t parent = start_rockdd(mc, tmp.path(), tmp.path() / "log");
  ASSERT_TRUE(poll_until([&] {
    return std::filesystem::exists(dir / "mc.csv") && lines_of(dir / "mc.csv").size() >= 2;
  })) << test::read_text(tmp.path() / "log");
  std::vector<pid_t> workers;
  poll_until([&] { return !(workers = children_of(parent)).empty(); }, 10.0);
  kill(parent, SIGKILL);
  int status = 0;
  waitpid(parent, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  // Its worker dies with it (it would go on writing into a seed folder the re-run redoes).
  for (const pid_t w : workers) EXPECT_TRUE(poll_until([&] { return !running(w); }, 10.0)) << w;

  const std::string text = test::read_text(dir / "mc.csv");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const std::vector<std::string> before = lines_of(dir / "mc.csv");
  ASSERT_GE(before.size(), 2u);
  ASSERT_LT(before.size(), 5u) << "killed too late: every row was there";
  for (const std::string& line : before) EXPECT_EQ(cells_in(line), cells_in(before[0])) << line;

  const auto rerun = rockdd_cli(mc, tmp.path());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  const std::vector<std::string> after = lines_of(dir / "mc.csv");
  ASSERT_EQ(after.size(), 5u);
  for (const std::string& line : before)
    EXPECT_NE(std::find(after.begin(), after.end(), line), after.end()) << line;
  for (std::size_t i = 1; i < after.size(); ++i)
    EXPECT_EQ(after[i].rfind(std::to_string(6 + i) + ",ok,", 0), 0u) << after[i];
}

TEST(MonteCarloCommand, AKilledWorkerIsACrashedRowThatTheRerunRunsAgain) {
  test::TempDir tmp;
  const std::string mc =
      "mc " + kScene + " --realizations 2 --first-seed 7 --threads 2 --jobs 1 --out mc" + kCoarse;
  const auto dir = tmp.path() / "mc" / kFolder;
  const pid_t parent = start_rockdd(mc, tmp.path(), tmp.path() / "log");
  // The parent first forks a check of the scene: seed 7's worker is the child named for it.
  pid_t worker = 0;
  ASSERT_TRUE(poll_until(
      [&] {
        for (const pid_t child : children_of(parent))
          if (name_of(child) == "seed 7") worker = child;
        return worker != 0;
      },
      60.0));
  kill(worker, SIGKILL);
  int status = 0;
  waitpid(parent, &status, 0);
  const std::string log = test::read_text(tmp.path() / "log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 1) << log;  // a crashed realization: not all ok
  const std::vector<std::string> rows = lines_of(dir / "mc.csv");
  ASSERT_EQ(rows.size(), 3u) << log;
  EXPECT_EQ(rows[1].substr(0, 10), "7,crashed,") << rows[1];
  EXPECT_NE(rows[1].find("killed by signal 9"), std::string::npos) << rows[1];
  EXPECT_EQ(rows[2].substr(0, 5), "8,ok,") << rows[2];
  const auto report = nlohmann::json::parse(test::read_text(dir / "mc.json"));
  EXPECT_EQ(report["crashed"], 1);
  EXPECT_EQ(report["failed"], 1);

  const auto rerun = rockdd_cli(mc, tmp.path());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("1 to run"), std::string::npos) << rerun.output;
  const std::vector<std::string> after = lines_of(dir / "mc.csv");
  ASSERT_EQ(after.size(), 3u);  // the crashed row replaced, not kept beside the new one
  EXPECT_EQ(after[1].substr(0, 5), "7,ok,") << after[1];
  EXPECT_EQ(after[2], rows[2]);
}

TEST(MonteCarloCommand, FramesOnlyWithTheFramesOption) {
  test::TempDir tmp;
  const auto inv = rockdd_cli("mc " + kScene +
                                  " --realizations 1 --first-seed 7 --threads 2 --frames --quiet "
                                  "--out mc" +
                                  kCoarse,
                              tmp.path());
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  const auto seed = tmp.path() / "mc" / kFolder / "seed_7";
  EXPECT_TRUE(std::filesystem::exists(seed / "frames.pvd"));
  EXPECT_TRUE(std::filesystem::exists(seed / "frames" / "frame_00000.vtu"));
  // --no-last-frame: none at all; the rows are the same.
  const auto none = rockdd_cli("mc " + kScene +
                                   " --realizations 1 --first-seed 7 --threads 2 --no-last-frame "
                                   "--quiet --out none" +
                                   kCoarse,
                               tmp.path());
  ASSERT_EQ(none.exit_code, 0) << none.output;
  const auto bare = tmp.path() / "none" / kFolder / "seed_7";
  EXPECT_TRUE(std::filesystem::exists(bare / "summary.json"));
  EXPECT_FALSE(std::filesystem::exists(bare / "frames"));
  EXPECT_FALSE(std::filesystem::exists(bare / "frames.pvd"));
  EXPECT_EQ(rows_without_wall_time(tmp.path() / "none" / kFolder / "mc.csv"),
            rows_without_wall_time(tmp.path() / "mc" / kFolder / "mc.csv"));
  // The ensemble's provenance: the scene's text and the command line as given.
  const auto provenance =
      nlohmann::json::parse(test::read_text(tmp.path() / "none" / kFolder / "mc.provenance.json"));
  EXPECT_EQ(provenance["scene"], "uniaxial-compression");
  EXPECT_EQ(provenance["scene_text"],
            test::read_text(kSource / "data/uniaxial_compression.toml"));
  ASSERT_EQ(provenance["runs"].size(), 1u);
  const auto& command = provenance["runs"][0]["command"];
  EXPECT_NE(std::find(command.begin(), command.end(), "--no-last-frame"), command.end());
  for (const char* key : {"started", "commit", "rockdd_version", "host"})
    EXPECT_TRUE(provenance["runs"][0].contains(key)) << key;
}

TEST(MonteCarloCommand, BadShardsAndMergesExitTwoNamingTheOption) {
  test::TempDir tmp;
  for (const char* shard : {"3/2", "x", "0/2", "1/0", "1/", "/2", "1/2/3"}) {
    const auto inv = rockdd_cli("mc " + kScene + " --realizations 2 --shard " + shard, tmp.path());
    EXPECT_EQ(inv.exit_code, 2) << shard << ": " << inv.output;
    EXPECT_NE(inv.output.find("--shard"), std::string::npos) << shard << ": " << inv.output;
    EXPECT_NE(inv.output.find(shard), std::string::npos) << shard << ": " << inv.output;
  }
  EXPECT_EQ(rockdd_cli("run " + kScene + " --shard 1/2", tmp.path()).exit_code, 2);
  EXPECT_EQ(rockdd_cli("run " + kScene + " --restart", tmp.path()).exit_code, 2);
  EXPECT_EQ(rockdd_cli("mc-merge out", tmp.path()).exit_code, 2);
  const auto missing = rockdd_cli("mc-merge out nowhere", tmp.path());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("nowhere"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "mc"));
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
  // An mc.csv of an older rockdd (no manifest) cannot be matched to the scene: refused.
  std::filesystem::create_directories(tmp.path() / "old" / kFolder);
  std::ofstream(tmp.path() / "old" / kFolder / "mc.csv") << "seed,status,steps,reason\n1,ok,3,\n";
  const auto old = rockdd_cli("mc " + kScene + " --realizations 2 --out old", tmp.path());
  EXPECT_EQ(old.exit_code, 2) << old.output;
  EXPECT_NE(old.output.find("--restart"), std::string::npos) << old.output;
  EXPECT_NE(old.output.find("mc.manifest.json"), std::string::npos) << old.output;
}

TEST(MonteCarloCommand, ASecondRunOnTheSameFolderIsRefusedWhileTheFirstRuns) {
  test::TempDir tmp;
  const std::string mc =
      "mc " + kScene + " --realizations 2 --first-seed 7 --threads 2 --jobs 1 --out mc" + kCoarse;
  const pid_t first = start_rockdd(mc, tmp.path(), tmp.path() / "log");
  ASSERT_TRUE(poll_until([&] { return !children_of(first).empty(); }, 60.0));
  const auto second = rockdd_cli(mc, tmp.path());
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find("mc.lock"), std::string::npos) << second.output;
  int status = 0;
  waitpid(first, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << test::read_text(tmp.path() / "log");
}

#ifdef ROCKDD_MPIEXEC
TEST(MonteCarloCommand, MpiRanksRefuseBadInputAndAHeldFolderAndAKilledRunResumes) {
  test::TempDir tmp;
  const std::string mpirun = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '" +
                             std::string(ROCKDD_MPIEXEC) + "' --oversubscribe -n 2 '" +
                             ROCKDD_BINARY + "' ";
  // Bad input: exit 2, the reader's message once (rank 0's; the other rank stays quiet).
  const auto bad = mpi_rockdd_cli(
      2, "mc " + kScene + " --realizations 2 --set material.0.young=-1 --out bad", tmp.path());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  const std::size_t at = bad.output.find("material[0].young");
  ASSERT_NE(at, std::string::npos) << bad.output;
  EXPECT_EQ(bad.output.find("material[0].young", at + 1), std::string::npos) << bad.output;

  // A folder another rockdd mc holds: rank 0 refuses, every rank ends, exit 2.
  const std::string held =
      "mc " + kScene + " --realizations 2 --first-seed 7 --threads 1 --jobs 1 --out held" + kCoarse;
  const pid_t first = start_rockdd(held, tmp.path(), tmp.path() / "held.log");
  ASSERT_TRUE(poll_until([&] { return !children_of(first).empty(); }, 60.0));
  const auto second = mpi_rockdd_cli(2, held, tmp.path());
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find("mc.lock"), std::string::npos) << second.output;
  int status = 0;
  waitpid(first, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);

  // mpirun stopped (SIGTERM, as scancel sends) after the first row: whole rows only, and the
  // rerun runs only the seeds without one.
  const std::string mc =
      "mc " + kScene + " --realizations 6 --first-seed 7 --threads 1 --out mc" + kCoarse;
  const auto dir = tmp.path() / "mc" / kFolder;
  const pid_t launcher = fork();
  if (launcher == 0) {
    const std::string command = "cd '" + tmp.path().string() + "' && exec env " + mpirun + mc +
                                " >'" + (tmp.path() / "mpi.log").string() + "' 2>&1";
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(poll_until([&] {
    return std::filesystem::exists(dir / "mc.csv") && lines_of(dir / "mc.csv").size() >= 2;
  })) << test::read_text(tmp.path() / "mpi.log");
  kill(launcher, SIGTERM);
  waitpid(launcher, &status, 0);
  const std::vector<std::string> kept = lines_of(dir / "mc.csv");
  ASSERT_GE(kept.size(), 2u);
  for (const std::string& line : kept) EXPECT_EQ(cells_in(line), cells_in(kept[0])) << line;
  const long done = static_cast<long>(kept.size()) - 1;
  const auto rerun = mpi_rockdd_cli(2, mc, tmp.path());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find(std::to_string(done) + " already in"), std::string::npos)
      << rerun.output;
  const auto rows = rows_without_wall_time(dir / "mc.csv");
  ASSERT_EQ(rows.size(), 6u);
  for (std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(rows[i].substr(0, rows[i].find(',') + 3), std::to_string(7 + i) + ",ok");
}
#endif

}  // namespace
}  // namespace rockdd

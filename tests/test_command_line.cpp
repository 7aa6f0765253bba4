// The rockdd command line as users and their scripts see it: exit codes, messages, files.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "engine/solver/blas_kernels.hpp"
#include "support/command_line.hpp"
#include "support/file_text.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

using test::Invocation;
using test::rockdd_cli;

const std::filesystem::path kSource = ROCKDD_SOURCE_DIR;

/// A CSV file's cells by column name, as text (mc.csv mixes numbers and words).
std::map<std::string, std::vector<std::string>> read_text_csv(const std::filesystem::path& file) {
  std::stringstream in(test::read_text(file));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) names.push_back(cell);
  std::map<std::string, std::vector<std::string>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t i = 0;
    for (std::string cell; i < names.size(); ++i) {
      std::getline(row, cell, ',');
      columns[names[i]].push_back(cell);
    }
  }
  return columns;
}

TEST(CommandLine, RunWritesEveryPromisedOutput) {
  test::TempDir tmp;
  const auto inv = rockdd_cli("run '" + (kSource / "data/cantilever_model_2.toml").string() +
                                  "' --out out --threads 2 --set output.every=1 --set time.steps=2",
                              tmp.path());
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  const auto dir = tmp.path() / "out" / "cantilever-model-2";
  const auto summary = nlohmann::json::parse(test::read_text(dir / "summary.json"));
  for (const char* key :
       {"status", "rockdd_version", "threads", "wall_seconds", "steps", "redone_steps",
        "open_close_iterations", "max_open_close_per_step", "damage_iterations", "elements",
        "nodes", "blocks", "damaged_elements", "peaks", "defaults", "timers", "solver"})
    EXPECT_TRUE(summary.contains(key)) << key;
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["threads"], 2);
  EXPECT_EQ(summary["steps"], 2);
  EXPECT_EQ(summary["elements"], 128);
  EXPECT_EQ(summary["solver"]["analyses"], 1);
  EXPECT_EQ(summary["solver"]["factorizations"], 1);  // static: K factorized once, reused
  for (const char* timer :
       {"assembly", "factorization", "solve", "contact", "damage", "detachment", "output"})
    EXPECT_TRUE(summary["timers"].contains(timer)) << timer;
  EXPECT_TRUE(summary["peaks"].contains("tip.uy"));

  const std::string history = test::read_text(dir / "history.csv");
  EXPECT_EQ(history.substr(0, history.find('\n')),
            "step,time,dt,tip.ux,tip.uy,support.fx,support.fy,energy.kinetic,energy.strain,"
            "energy.external_work,energy.dissipated,energy.snap_back,energy.integrator,"
            "energy.anchor_work,energy.quasi_static_loss,energy.unaccounted");
  EXPECT_EQ(std::count(history.begin(), history.end(), '\n'), 4);  // header + steps 0, 1, 2
  for (const char* frame : {"frame_00000.vtu", "frame_00001.vtu", "frame_00002.vtu"})
    EXPECT_TRUE(std::filesystem::exists(dir / "frames" / frame)) << frame;
  const std::string pvd = test::read_text(dir / "frames.pvd");
  EXPECT_NE(pvd.find("file=\"frames/frame_00002.vtu\""), std::string::npos) << pvd;
  EXPECT_TRUE(std::filesystem::exists(dir / "profiles" / "midline_000002.csv"));
  const std::string profile = test::read_text(dir / "profiles" / "midline_000002.csv");
  EXPECT_EQ(profile.substr(0, profile.find('\n')), "s,x,y,ux,uy,sxx");
  // No temporary file is left behind.
  for (const auto& f : std::filesystem::recursive_directory_iterator(dir))
    EXPECT_EQ(f.path().filename().string().find(".tmp"), std::string::npos) << f.path();
}

TEST(CommandLine, ResultsDoNotDependOnTheThreadCount) {
  test::TempDir tmp;
  const std::string scene = (kSource / "data/brazilian_disk_elastic.toml").string();
  ASSERT_EQ(rockdd_cli("run '" + scene + "' --quiet --threads 1 --out one", tmp.path()).exit_code,
            0);
  ASSERT_EQ(rockdd_cli("run '" + scene + "' --quiet --threads 2 --out two", tmp.path()).exit_code,
            0);
  for (const char* file : {"history.csv", "profiles/diameter_000001.csv", "frames/frame_00001.vtu"})
    EXPECT_EQ(test::read_text(tmp.path() / "one/brazilian-disk-elastic" / file),
              test::read_text(tmp.path() / "two/brazilian-disk-elastic" / file))
        << file;
}

TEST(CommandLine, ASecondRunTakesItsMeshFromTheCacheAndGivesTheSameResults) {
  test::TempDir tmp;
  const std::string scene = (kSource / "data/brazilian_disk_elastic.toml").string();
  const std::string cache = " --mesh-cache '" + (tmp.path() / "cache").string() + "'";
  for (const char* out : {"first", "second"})
    ASSERT_EQ(rockdd_cli("run '" + scene + "' --quiet --out " + out + cache, tmp.path()).exit_code,
              0);
  ASSERT_EQ(
      rockdd_cli("run '" + scene + "' --quiet --out off --mesh-cache off", tmp.path()).exit_code,
      0);
  const auto summary = [&](const char* out) {
    return nlohmann::json::parse(
        test::read_text(tmp.path() / out / "brazilian-disk-elastic/summary.json"));
  };
  EXPECT_EQ(summary("first")["mesh_cache"], "miss");
  EXPECT_EQ(summary("second")["mesh_cache"], "hit");
  EXPECT_EQ(summary("off")["mesh_cache"], "off");
  for (const char* file : {"history.csv", "frames/frame_00001.vtu"}) {
    const std::string first = test::read_text(tmp.path() / "first/brazilian-disk-elastic" / file);
    EXPECT_EQ(test::read_text(tmp.path() / "second/brazilian-disk-elastic" / file), first) << file;
    EXPECT_EQ(test::read_text(tmp.path() / "off/brazilian-disk-elastic" / file), first) << file;
  }
}

TEST(CommandLine, GmshIsLoadedOnlyToMesh) {
  // Gmsh and its ~90 libraries took 0.14 s to load in every process: they live in
  // librockdd_gmsh.so, which build_mesh opens on first use. A mesh-cache miss loads Gmsh
  // (the dynamic loader's LD_DEBUG=files names libgmsh), a hit and --version never do.
  test::TempDir tmp;
  const std::string scene = (kSource / "data/brazilian_disk_elastic.toml").string();
  const std::string cache = " --mesh-cache '" + (tmp.path() / "cache").string() + "'";
  const auto loaded = [&](const std::string& args) {
    const test::Invocation run =
        test::run_shell("cd '" + tmp.path().string() + "' && LD_DEBUG=files '" + ROCKDD_BINARY +
                        "' " + args + " 2>&1");
    EXPECT_EQ(run.exit_code, 0) << args;
    return run.output.find("libgmsh") != std::string::npos;
  };
  EXPECT_FALSE(loaded("--version"));
  EXPECT_TRUE(loaded("run '" + scene + "' --quiet --out miss" + cache));
  EXPECT_FALSE(loaded("run '" + scene + "' --quiet --out hit" + cache));
  EXPECT_EQ(nlohmann::json::parse(test::read_text(
                tmp.path() / "hit/brazilian-disk-elastic/summary.json"))["mesh_cache"],
            "hit");
}

TEST(CommandLine, OpenBlasFallingBackToPrescottIsRestartedWithHaswellUnlessASetIsNamed) {
  // OpenBLAS names the set it loads when OPENBLAS_VERBOSE=2: OpenBLAS's own choice first and,
  // after a restart, the set rockdd asked for. A set the environment names is kept, and the
  // restarted process is the same command: its output and exit status.
  test::TempDir tmp;
  const auto sets_loaded = [&](const std::string& environment, const std::string& args) {
    const test::Invocation run = test::run_shell(
        "cd '" + tmp.path().string() + "' && env -u OPENBLAS_CORETYPE OPENBLAS_VERBOSE=2 " +
        environment + " '" + ROCKDD_BINARY + "' " + args + " 2>&1");
    std::vector<std::string> sets;
    const std::regex core("Core: (\\S+)");
    for (std::sregex_iterator it(run.output.begin(), run.output.end(), core), end; it != end; ++it)
      sets.push_back((*it)[1]);
    return std::make_pair(sets, run);
  };
  const auto [own_sets, version] = sets_loaded("", "--version");
  ASSERT_FALSE(own_sets.empty()) << version.output;
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.output.find("rockdd "), std::string::npos);
  const std::string own = own_sets.front();
  const std::string better = better_blas_kernel_set(own, cpu_vector_features());
  if (better.empty())
    EXPECT_EQ(own_sets, std::vector<std::string>{own});
  else
    EXPECT_EQ(own_sets, (std::vector<std::string>{own, better}));

  const auto [named_sets, named] = sets_loaded("OPENBLAS_CORETYPE=Prescott", "--version");
  EXPECT_EQ(named_sets, std::vector<std::string>{"Prescott"}) << named.output;

  const std::string scene = (kSource / "data/cantilever_model_1.toml").string();
  const auto [run_sets, run] = sets_loaded("", "run '" + scene + "' --quiet --out out");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(nlohmann::json::parse(test::read_text(
                tmp.path() / "out/cantilever-model-1/summary.json"))["solver"]["blas_kernels"],
            run_sets.back());
  const auto [bad_sets, bad] = sets_loaded("", "run no-such-scene.toml --quiet");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("no-such-scene.toml"), std::string::npos) << bad.output;
}

TEST(CommandLine, UnderValgrindRockddDoesNotRestartItself) {
  // An exec leaves valgrind, and tools/bench-track's callgrind counts would stop at it. rockdd
  // knows valgrind by the vgpreload library its launcher preloads: a harmless library under
  // that name stands in for it (so that OpenBLAS, run natively, falls back as it does here),
  // then valgrind itself runs rockdd to its end.
  test::TempDir tmp;
  const std::filesystem::path fake = tmp.path() / "vgpreload_stand_in.so";
  std::filesystem::create_symlink("/lib/x86_64-linux-gnu/libm.so.6", fake);
  const auto cores = [](const std::string& output) {
    std::size_t count = 0;
    for (std::size_t at = output.find("Core: "); at != std::string::npos;
         at = output.find("Core: ", at + 1))
      ++count;
    return count;
  };
  const test::Invocation stand_in =
      test::run_shell("env -u OPENBLAS_CORETYPE OPENBLAS_VERBOSE=2 LD_PRELOAD='" + fake.string() +
                      "' '" + ROCKDD_BINARY + "' --version 2>&1");
  EXPECT_EQ(stand_in.exit_code, 0) << stand_in.output;
  EXPECT_EQ(cores(stand_in.output), 1U) << stand_in.output;

  if (test::run_shell("command -v valgrind >/dev/null").exit_code != 0)
    GTEST_SKIP() << "valgrind is not installed";
  const test::Invocation run =
      test::run_shell("env -u OPENBLAS_CORETYPE OPENBLAS_VERBOSE=2 valgrind --tool=none -q '" +
                      std::string(ROCKDD_BINARY) + "' --version 2>&1");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("rockdd "), std::string::npos) << run.output;
  EXPECT_EQ(cores(run.output), 1U) << run.output;
}

TEST(CommandLine, AStoredOrderingGivesBitwiseTheResultsOfComputingIt) {
  // The fill-reducing ordering is kept beside the cached mesh: a run that reads it (hit)
  // writes bitwise the files of one that computed it (miss) and of one without a cache; a
  // damaged stored ordering is a miss, computed and stored again.
  test::TempDir tmp;
  const std::string scene = (kSource / "data/brazilian_disk_elastic.toml").string();
  const std::filesystem::path cache_dir = tmp.path() / "cache";
  const std::string cache = " --mesh-cache '" + cache_dir.string() + "'";
  const auto run = [&](const std::string& out, const std::string& cache_option) {
    ASSERT_EQ(
        rockdd_cli("run '" + scene + "' --quiet --out " + out + cache_option, tmp.path()).exit_code,
        0);
  };
  const auto summary = [&](const std::string& out) {
    return nlohmann::json::parse(
        test::read_text(tmp.path() / out / "brazilian-disk-elastic/summary.json"));
  };
  const auto order_entry = [&] {
    std::vector<std::filesystem::path> found;
    for (const auto& e : std::filesystem::directory_iterator(cache_dir))
      if (e.path().extension() == ".order") found.push_back(e.path());
    return found;
  };
  run("miss", cache);
  run("hit", cache);
  ASSERT_EQ(order_entry().size(), 1u);
  const std::filesystem::path entry = order_entry().front();
  {
    const auto size = std::filesystem::file_size(entry);
    std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size - size / 10));  // inside the stored ordering
    f.put('\x55');
  }
  run("mangled", cache);
  run("again", cache);
  run("off", " --mesh-cache off");
  EXPECT_EQ(summary("miss")["solver"]["ordering_cache"], "miss");
  EXPECT_EQ(summary("hit")["solver"]["ordering_cache"], "hit");
  EXPECT_EQ(summary("mangled")["solver"]["ordering_cache"], "miss");
  EXPECT_EQ(summary("again")["solver"]["ordering_cache"], "hit");
  EXPECT_EQ(summary("off")["solver"]["ordering_cache"], "off");
  for (const char* out : {"hit", "mangled", "again", "off"}) {
    SCOPED_TRACE(out);
    for (const char* key : {"ordering", "factor_nonzeros", "factor_flops", "nonzeros"})
      EXPECT_EQ(summary(out)["solver"][key], summary("miss")["solver"][key]) << key;
    for (const char* file :
         {"history.csv", "frames/frame_00001.vtu", "profiles/diameter_000001.csv"})
      EXPECT_EQ(test::read_text(tmp.path() / out / "brazilian-disk-elastic" / file),
                test::read_text(tmp.path() / "miss/brazilian-disk-elastic" / file))
          << file;
  }
}

TEST(CommandLine, SummaryTimersAccountForTheWholeProcess) {
  test::TempDir tmp;
  const std::string scene = (kSource / "data/brazilian_disk_elastic.toml").string();
  ASSERT_EQ(rockdd_cli("run '" + scene + "' --quiet --out out", tmp.path()).exit_code, 0);
  const auto s = nlohmann::json::parse(
      test::read_text(tmp.path() / "out/brazilian-disk-elastic/summary.json"));
  const auto& t = s["timers"];
  double named = s["wall_seconds"].get<double>();
  for (const char* key :
       {"startup", "scene", "meshing", "model", "setup", "setup_layout", "setup_analysis"}) {
    ASSERT_TRUE(t.contains(key)) << key;
    EXPECT_GE(t[key].get<double>(), 0.0) << key;
    named += t[key].get<double>();
  }
  double stages = t["step_other"].get<double>();
  for (const char* key : {"assembly", "factorization", "solve", "contact", "damage", "detachment",
                          "output", "layout", "analysis"})
    stages += t[key].get<double>();
  // The step stages are exclusive (a nested timer pauses its outer one): they add up to the
  // run's wall time exactly, step_other being the rest.
  EXPECT_NEAR(stages, s["wall_seconds"].get<double>(), 1e-9);
  // CHOLMOD's symbolic phase runs beside the scatter map and the assembly: the timers count
  // what the steps waited for it (set-up none), the solver its own time, wherever it ran.
  EXPECT_EQ(t["setup_analysis"].get<double>(), 0.0);
  EXPECT_GT(s["solver"]["analysis_seconds"].get<double>(), 0.0);
  // The process's age comes from /proc in 10 ms ticks; the gaps between timers are small.
  const double process = t["process"].get<double>();
  EXPECT_NEAR(t["unaccounted"].get<double>(), process - named, 1e-9);
  EXPECT_LT(std::abs(t["unaccounted"].get<double>()), 0.02 + 0.05 * process) << s.dump(1);
}
TEST(CommandLine, CheckPrintsCountsAndDefaultsWithoutSolving) {
  test::TempDir tmp;
  const auto inv =
      rockdd_cli("check '" + (kSource / "data/cantilever_model_1.toml").string() + "'", tmp.path());
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  EXPECT_NE(inv.output.find("elements: 32"), std::string::npos) << inv.output;
  EXPECT_NE(inv.output.find("blocks: 1"), std::string::npos) << inv.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

TEST(CommandLine, CheckPrintsTheStepsAndTheirTime) {
  // Issue 28: the run's length before the run. 1600 steps of 0.00625 s to time.end = 10 s on
  // 8,100 elements: 0.69 to 8.3 us a step per element (step_budget.hpp).
  test::TempDir tmp;
  const auto inv = rockdd_cli(
      "check '" + (kSource / "data/uniaxial_compression.toml").string() + "'", tmp.path());
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  EXPECT_NE(inv.output.find("steps: 1600 (budget 10000000, time.max_steps), fewer when the run "
                            "ends on softening"),
            std::string::npos)
      << inv.output;
  EXPECT_NE(inv.output.find("estimated run time: 8.9 to 1.1e+02 s"), std::string::npos)
      << inv.output;
  // time.max_steps raises the budget; the same scene under a lower one is refused.
  const std::string scene = (kSource / "data/uniaxial_compression.toml").string();
  EXPECT_EQ(rockdd_cli("check '" + scene + "' --set time.max_steps=1600", tmp.path()).exit_code, 0);
  const auto refused = rockdd_cli("check '" + scene + "' --set time.max_steps=1599", tmp.path());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("time.dt: expected at most time.max_steps = 1599 steps, got "
                                "time.end / time.dt = 10 / 0.00625 = 1600 steps"),
            std::string::npos)
      << refused.output;
}

TEST(CommandLine, TheLastStepIsNeverShorterThanDtMin) {
  // Issue 28: a remainder of time.end shorter than dt_min (here 1e-9 s after four steps of
  // 0.25 s, dt_min = 2.5e-7) was a step of its own; it is merged into the step before.
  test::TempDir tmp;
  const auto inv = rockdd_cli("run '" + (kSource / "data/cantilever_model_1.toml").string() +
                                  "' --out out --quiet --set time.end=1.000000001 "
                                  "--set time.dt=0.25",
                              tmp.path());
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  const auto dir = tmp.path() / "out" / "cantilever-model-1";
  const auto summary = nlohmann::json::parse(test::read_text(dir / "summary.json"));
  EXPECT_EQ(summary["steps"], 4);
  const auto history = read_text_csv(dir / "history.csv");
  ASSERT_EQ(history.at("dt").size(), 5u);  // step 0 and four steps
  EXPECT_DOUBLE_EQ(std::stod(history.at("dt").back()), 0.25 + 1e-9);
  EXPECT_DOUBLE_EQ(std::stod(history.at("time").back()), 1.000000001);
}

TEST(CommandLine, EveryMalformedSceneExitsTwoNamingFileAndKeyAndWritesNothing) {
  // tests/scenes/bad/CASES.md lists each case with the key its message must name.
  const auto bad = kSource / "tests/scenes/bad";
  const std::string cases = test::read_text(bad / "CASES.md");
  const std::regex row(R"(\|\s*`?([A-Za-z0-9_\-]+\.toml)`?\s*\|\s*`([^`]+)`)");
  int checked = 0;
  for (auto it = std::sregex_iterator(cases.begin(), cases.end(), row);
       it != std::sregex_iterator(); ++it) {
    const std::string file = (*it)[1], key = (*it)[2];
    test::TempDir tmp;
    // A time limit: a scene that makes the engine hang (issue 13) fails here with 124.
    const auto inv = rockdd_cli("run '" + (bad / file).string() + "' --out out", tmp.path(), 60);
    EXPECT_EQ(inv.exit_code, 2) << file << ": " << inv.output;
    EXPECT_NE(inv.output.find(file), std::string::npos) << file << ": " << inv.output;
    EXPECT_NE(inv.output.find(key), std::string::npos)
        << file << " should name " << key << ": " << inv.output;
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << file << " wrote outputs";
    ++checked;
  }
  EXPECT_GE(checked, 15);
}

TEST(CommandLine, BadMeshesExitTwoNamingTheMeshKeyAndWriteNothing) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"msh", "quad.msh"},
      {"msh", "zero_area.msh"},
      {"msh", "truncated.msh"},
      {"geo", "syntax_error.geo"},
      {"geo", "unmeshable.geo"},
      {"geo", "stray_curve.geo"},
      {"geo", "second_order.geo"},
      {"msh", "does_not_exist.msh"},
      {"msh", "geo_script.msh"},
      {"msh", "misspelled_header.msh"},
      {"msh", "binary_flag_on_text.msh"},
      {"msh", "element_names_undefined_node.msh"},
      {"msh", "node_line_split.msh"},
      {"msh", "physical_name_dimension_4.msh"},
      {"msh", "element_parent_tag.msh"},
      {"msh", "element_partition_tags.msh"},
      {"msh", "two_node_sections.msh"},
      {"msh", "element_count_unreadable.msh"},
      // Issue 28: heap corruption (exit 134) and SIGSEGV (139) in Gmsh's format-4 reader.
      {"msh", "msh4_node_count_short.msh"},
      {"msh", "msh4_node_count_zero.msh"},
      {"msh", "msh4_element_count_short.msh"},
      {"msh", "msh4_element_node_negative.msh"},
      {"msh", "msh4_binary_node_count_short.msh"},
      // Issue 28: .geo files that meshed without limit (GBs within a minute).
      {"geo", "kirsch_point_far.geo"},
      {"geo", "lame_size_1e-300.geo"},
      {"geo", "hondros_size_1e-9.geo"},
      {"geo", "size_field_1e-4.geo"},
  };
  // Issue 28's cases say what was expected and name the mesh file (its line for .msh).
  const std::set<std::string> issue_28 = {"msh4_node_count_short.msh",
                                          "msh4_node_count_zero.msh",
                                          "msh4_element_count_short.msh",
                                          "msh4_element_node_negative.msh",
                                          "msh4_binary_node_count_short.msh",
                                          "kirsch_point_far.geo",
                                          "lame_size_1e-300.geo",
                                          "hondros_size_1e-9.geo"};
  for (const auto& [kind, file] : cases) {
    test::TempDir tmp;
    std::ofstream(tmp.path() / "scene.toml")
        << "[scene]\nname = \"bad-mesh\"\n[mesh]\n"
        << kind << " = \"" << (kSource / "tests/meshes" / file).string()
        << "\"\n[[material]]\ndensity = 2000.0\nyoung = 1e9\npoisson = 0.2\n";
    for (const char* verb : {"run", "check"}) {
      // A time limit: a mesh that ran without limit fails here with 124, not after minutes.
      const std::string out = std::string(verb) == "run" ? " --out out" : "";  // check writes none
      const auto inv = rockdd_cli(std::string(verb) + " scene.toml" + out, tmp.path(), 60);
      EXPECT_EQ(inv.exit_code, 2) << verb << ' ' << file << ": " << inv.output;
      EXPECT_NE(inv.output.find("mesh." + kind), std::string::npos) << file << ": " << inv.output;
      if (issue_28.count(file)) {
        EXPECT_NE(inv.output.find("mesh." + kind + ": expected"), std::string::npos)
            << file << ": " << inv.output;
        EXPECT_NE(inv.output.find("tests/meshes/" + file), std::string::npos)
            << file << ": " << inv.output;
      }
      EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << file;
    }
  }
}

TEST(CommandLine, MonteCarloRefusesABadMeshBeforeAnyWorkerOrFolder) {
  // Issue 28: with a format-4.1 mesh Gmsh's reader corrupts its heap on, every worker was
  // "crashed: signal 6" and the ensemble exited 1 with its folder written. The first
  // realization is now built, as `rockdd check` builds it, before anything else.
  test::TempDir tmp;
  std::ofstream(tmp.path() / "scene.toml")
      << "[scene]\nname = \"bad-mesh\"\n[mesh]\nmsh = \""
      << (kSource / "tests/meshes/msh4_node_count_short.msh").string()
      << "\"\n[[material]]\ndensity = 2000.0\nyoung = 1e9\npoisson = 0.2\n"
         "tensile_strength = 1e6\nhomogeneity = 1.5\nheterogeneous = [\"young\"]\nseed = 1\n"
         "[[boundary]]\non = \"bottom\"\nfix = [\"x\", \"y\"]\n";
  const auto mc = rockdd_cli("mc scene.toml --realizations 2 --out mc", tmp.path(), 60);
  EXPECT_EQ(mc.exit_code, 2) << mc.output;
  EXPECT_NE(mc.output.find("scene.toml: mesh.msh: expected the blocks of $Nodes to hold the 1 "
                           "nodes its header declares (line 24)"),
            std::string::npos)
      << mc.output;
  EXPECT_EQ(mc.output.find("crashed"), std::string::npos) << mc.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "mc"));
}

TEST(CommandLine, UsageErrorsExitTwo) {
  test::TempDir tmp;
  EXPECT_EQ(rockdd_cli("", tmp.path()).exit_code, 2);
  EXPECT_EQ(rockdd_cli("frobnicate x.toml", tmp.path()).exit_code, 2);
  EXPECT_EQ(rockdd_cli("run", tmp.path()).exit_code, 2);
  EXPECT_EQ(rockdd_cli("run a.toml --threads 0", tmp.path()).exit_code, 2);
  EXPECT_EQ(rockdd_cli("run a.toml --bogus", tmp.path()).exit_code, 2);
  const auto missing = rockdd_cli("run does_not_exist.toml", tmp.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("does_not_exist.toml"), std::string::npos) << missing.output;
  EXPECT_EQ(rockdd_cli("--version", tmp.path()).exit_code, 0);
}

TEST(CommandLine, MonteCarloRunsOneRealizationPerSeedAndTabulatesThem) {
  // Three seeds of the uniaxial compression specimen (900 elements), two at a time: each
  // realization's summary is the one `rockdd run` gives for that seed, bit for bit (the
  // worker processes change nothing), and mc.csv / mc.json tabulate the peaks with their
  // mean and sample standard deviation.
  test::TempDir tmp;
  const std::string scene = (kSource / "data/uniaxial_compression.toml").string();
  const std::string mesh = " --set 'mesh.divisions=[15, 30]'";
  const auto mc = rockdd_cli(
      "mc '" + scene + "' --realizations 3 --first-seed 7 --threads 2 --out mc" + mesh, tmp.path());
  ASSERT_EQ(mc.exit_code, 0) << mc.output;
  const auto dir = tmp.path() / "mc" / "uniaxial-compression";
  const auto table = read_text_csv(dir / "mc.csv");
  ASSERT_EQ(table.at("seed"), (std::vector<std::string>{"7", "8", "9"}));
  ASSERT_EQ(table.at("status"), (std::vector<std::string>{"ok", "ok", "ok"}));
  std::vector<double> peaks;
  for (const std::string& cell : table.at("peaks.top.fy")) peaks.push_back(std::stod(cell));
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_NE(peaks[0], peaks[1]);
  const auto report = nlohmann::json::parse(test::read_text(dir / "mc.json"));
  EXPECT_EQ(report["ok"], 3);
  EXPECT_EQ(report["first_seed"], 7);
  const double mean = (peaks[0] + peaks[1] + peaks[2]) / 3.0;
  double squares = 0.0;
  for (const double p : peaks) squares += (p - mean) * (p - mean);
  const auto& stats = report["statistics"]["peaks.top.fy"];
  EXPECT_NEAR(stats["mean"].get<double>(), mean, 1e-12 * mean);
  EXPECT_NEAR(stats["std"].get<double>(), std::sqrt(squares / 2.0), 1e-9 * mean);
  // The same seed through `rockdd run` (one thread): the same history, bit for bit.
  const auto run = rockdd_cli(
      "run '" + scene + "' --out single --threads 1 --set material.0.seed=8" + mesh, tmp.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(test::read_text(dir / "seed_8" / "history.csv"),
            test::read_text(tmp.path() / "single/uniaxial-compression/history.csv"));
  // The realization kept its last frame (issue 31): the run's last frame, bit for bit.
  const auto summary = nlohmann::json::parse(test::read_text(dir / "seed_8" / "summary.json"));
  char last[32];
  std::snprintf(last, sizeof last, "frames/frame_%05ld.vtu", summary["steps"].get<long>());
  const std::string frame = test::read_text(dir / "seed_8" / last);
  EXPECT_FALSE(frame.empty()) << last;
  EXPECT_EQ(frame, test::read_text(tmp.path() / "single/uniaxial-compression" / last));
}

TEST(CommandLine, MonteCarloNeedsAHeterogeneousScene) {
  test::TempDir tmp;
  const std::string scene = (kSource / "data/cantilever_model_1.toml").string();
  const auto mc = rockdd_cli("mc '" + scene + "' --realizations 3 --out mc", tmp.path());
  EXPECT_EQ(mc.exit_code, 2) << mc.output;
  EXPECT_NE(mc.output.find("heterogeneous"), std::string::npos) << mc.output;
  EXPECT_NE(mc.output.find("cantilever_model_1.toml"), std::string::npos) << mc.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "mc"));
  EXPECT_EQ(rockdd_cli("run '" + scene + "' --realizations 2", tmp.path()).exit_code, 2);
}

TEST(CommandLine, NumericalFailureExitsOneWithTheReason) {
  // A displacement limit that no step can meet halves dt until it falls below dt_min.
  test::TempDir tmp;
  const auto inv = rockdd_cli(
      "run '" + (kSource / "data/cantilever_model_1.toml").string() +
          "' --out out --set scene.analysis='\"quasi-static\"' --set time.dt=1.0 --set time.steps=2"
          " --set time.max_step_displacement=1e-12 --set time.dt_min=1e-3",
      tmp.path());
  EXPECT_EQ(inv.exit_code, 1) << inv.output;
  EXPECT_NE(inv.output.find("max_step_displacement"), std::string::npos) << inv.output;
  EXPECT_NE(inv.output.find("dt_min"), std::string::npos) << inv.output;
  const auto summary =
      nlohmann::json::parse(test::read_text(tmp.path() / "out/cantilever-model-1/summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_TRUE(summary.contains("reason"));
}

// ---------------------------------------------------------------------------------------------
// Issue 31: each command's help and options, and the progress line.

TEST(CommandLine, EachCommandsHelpListsItsOptionsWithDefaultsAndExitsZero) {
  test::TempDir tmp;
  const std::map<std::string, std::vector<std::string>> options = {
      {"run", {"SCENE", "--out", "--threads", "--set", "--quiet", "--mesh-cache"}},
      {"check", {"SCENE", "--set", "--mesh-cache"}},
      {"mc",
       {"SCENE", "--realizations", "--first-seed", "--threads", "--jobs", "--out", "--shard",
        "--restart", "--frames", "--no-last-frame", "--set", "--quiet", "--mesh-cache"}},
      {"mc-merge", {"OUTDIR", "--quiet"}}};
  for (const auto& [verb, names] : options) {
    for (const char* flag : {" --help", " -h"}) {
      SCOPED_TRACE(verb + flag);
      const auto help = rockdd_cli(verb + flag, tmp.path());
      EXPECT_EQ(help.exit_code, 0) << help.output;
      EXPECT_NE(help.output.find("Usage: rockdd " + verb + " [OPTIONS]"), std::string::npos)
          << help.output;
      for (const std::string& name : names)
        EXPECT_NE(help.output.find("  " + name), std::string::npos) << name << "\n" << help.output;
      EXPECT_NE(help.output.find("Exit status: 0 success"), std::string::npos) << help.output;
    }
    // Every option but the positional ones says what it defaults to.
    const auto help = rockdd_cli(verb + " --help", tmp.path());
    std::vector<std::string> lines;
    std::stringstream text(help.output);
    for (std::string line; std::getline(text, line);) lines.push_back(line);
    int described = 0;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].rfind("  --", 0) == 0 && lines[i].find("--help") == std::string::npos) {
        std::string option = lines[i];
        for (std::size_t j = i + 1; j < lines.size() && lines[j].rfind("      ", 0) == 0; ++j)
          option += lines[j];  // the description's wrapped lines
        EXPECT_TRUE(option.find("default") != std::string::npos ||
                    option.find("required") != std::string::npos)
            << verb << ": " << option;
        ++described;
      }
    EXPECT_GE(described, static_cast<int>(names.size()) - 2) << help.output;
  }
  // A help option wins over everything else on the line, and runs nothing.
  EXPECT_EQ(rockdd_cli("run no_such.toml --out out --help", tmp.path()).exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

TEST(CommandLine, AnOptionTheCommandDoesNotTakeIsRefusedNamingIt) {
  test::TempDir tmp;
  const std::string scene = " '" + (kSource / "data/cantilever_model_1.toml").string() + "'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"check" + scene + " --out out", "rockdd check: unknown option '--out'"},
      {"check" + scene + " --threads 2", "rockdd check: unknown option '--threads'"},
      {"check" + scene + " --quiet", "rockdd check: unknown option '--quiet'"},
      {"run" + scene + " --realizations 2", "rockdd run: unknown option '--realizations'"},
      {"run" + scene + " --frames", "rockdd run: unknown option '--frames'"},
      {"run" + scene + " --bogus=3", "rockdd run: unknown option '--bogus'"},
      {"mc-merge out a b --threads 2", "rockdd mc-merge: unknown option '--threads'"},
      {"run" + scene + " second.toml", "rockdd run: unexpected argument 'second.toml'"},
      {"run" + scene + " --threads 0", "rockdd run: --threads expects an integer >= 1, got '0'"},
      {"mc" + scene + " --realizations 2 --frames --no-last-frame", "--frames excludes"},
      {"mc" + scene, "rockdd mc: --realizations is required"},
      {"frobnicate" + scene, "unknown command 'frobnicate'"}};
  for (const auto& [args, message] : cases) {
    const auto inv = rockdd_cli(args, tmp.path());
    EXPECT_EQ(inv.exit_code, 2) << args << ": " << inv.output;
    EXPECT_NE(inv.output.find(message), std::string::npos) << args << ": " << inv.output;
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << args;
  }
  // The refusal lists what the command takes.
  const auto check = rockdd_cli("check" + scene + " --out out", tmp.path());
  EXPECT_NE(check.output.find("check takes --set, --mesh-cache"), std::string::npos)
      << check.output;
  // Every spelling the README shows still runs: check with --set and --mesh-cache, run with
  // each of its options, --set=value and the value apart.
  EXPECT_EQ(rockdd_cli("check" + scene + " --set time.steps=2 --mesh-cache off", tmp.path()).exit_code,
            0);
  const auto run = rockdd_cli("run" + scene +
                                  " --out spelled --threads 1 --set time.steps=2 "
                                  "--set=output.every=1 --quiet --mesh-cache off",
                              tmp.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, "");  // --quiet
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "spelled/cantilever-model-1/frames/frame_00001.vtu"));
}

TEST(CommandLine, HelpNamesWhereTheExampleScenesAndTheSceneReferenceAre) {
  test::TempDir tmp;
  const auto help = rockdd_cli("--help", tmp.path());
  EXPECT_EQ(help.exit_code, 0);
  const std::smatch found = [&] {
    std::smatch m;
    std::regex_search(help.output, m, std::regex("every output: (\\S+/docs/scene\\.md)"));
    return m;
  }();
  ASSERT_FALSE(found.empty()) << help.output;
  EXPECT_TRUE(std::filesystem::is_regular_file(found[1].str())) << found[1];
  std::smatch scenes;
  ASSERT_TRUE(std::regex_search(help.output, scenes, std::regex("Example scenes: (\\S+)")));
  EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::path(scenes[1].str()) /
                                               "uniaxial_compression.toml"))
      << scenes[1];
  for (const char* command : {"run", "check", "mc", "mc-merge"})
    EXPECT_NE(help.output.find(std::string("  ") + command + " "), std::string::npos) << command;
}

/// The coarse compression specimen (400 elements) that ends on softening at 70 % below its
/// peak, long before time.end.
TEST(CommandLine, SpecimenThatFallsApartEndsThereAndSaysWhichStep) {
  // Issue 30: in plane stress the confined homogeneous specimen breaks into loose triangles
  // (at growth_tolerance 1e-3 every block is a fragment); the run ends ok at that step and says
  // so, and the energy warning says why its balance is open (docs/method-choices.md, "A
  // specimen that falls apart").
  test::TempDir tmp;
  const auto inv = test::run_shell(
      "cd '" + tmp.path().string() + "' && '" + ROCKDD_BINARY + "' run '" +
      (kSource / "data/verification/ucs_confined.toml").string() +
      "' --threads 1 --set 'scene.plane=\"stress\"' --set fracture.growth_tolerance=1e-3 "
      "--out out 2>&1");
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  const auto summary =
      nlohmann::json::parse(test::read_text(tmp.path() / "out/ucs-confined/summary.json"));
  ASSERT_TRUE(summary.contains("disintegration")) << inv.output;
  const std::string step = std::to_string(summary["disintegration"]["step"].get<long>());
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_NE(inv.output.find(", ended at step " + step + " (t = "), std::string::npos)
      << inv.output;
  EXPECT_NE(inv.output.find("loose fragments"), std::string::npos) << inv.output;
  // The log's last progress line says the run is done, with nothing left to wait for.
  EXPECT_NE(inv.output.find("100.0% done  ended: fell apart"), std::string::npos) << inv.output;
  EXPECT_NE(inv.output.find("ETA 00:00:00"), std::string::npos) << inv.output;
  EXPECT_NE(inv.output.find("its last step (" + step + ") broke the specimen"),
            std::string::npos)
      << inv.output;
  // At the default growth_tolerance (3e-4) a block of 3.8 % of it is left hanging from the
  // top platen: the run ends because nothing joins the platens, and says that instead.
  const auto hanging = test::run_shell(
      "cd '" + tmp.path().string() + "' && '" + ROCKDD_BINARY + "' run '" +
      (kSource / "data/verification/ucs_confined.toml").string() +
      "' --threads 1 --set 'scene.plane=\"stress\"' --out out2 2>&1");
  ASSERT_EQ(hanging.exit_code, 0) << hanging.output;
  EXPECT_NE(hanging.output.find("no chain of rock and closed contacts joins the moving boundary "
                                "to a held one any more"),
            std::string::npos)
      << hanging.output;
  EXPECT_NE(hanging.output.find("100.0% done  ended: fell apart"), std::string::npos)
      << hanging.output;
  EXPECT_NE(hanging.output.find("left no chain of rock and closed contacts"), std::string::npos)
      << hanging.output;
}

const std::string kSoftening = "run '" + (kSource / "data/uniaxial_compression.toml").string() +
                               "' --threads 2 --set 'mesh.divisions=[10, 20]' --out out";

TEST(CommandLine, ProgressInALogFollowsTheSofteningEndWithRateAndEta) {
  // Issue 31: a run that ended on softening at 14.5 % of time.end printed "ETA 102 s" last,
  // and a log got a line at step 1, one at 4.9 s and none for the next 16 s. Here the lines
  // come every 0.01 s (ROCKDD_PROGRESS_SECONDS; 10 s by default) besides each tenth of the
  // run, which takes about 0.4 s.
  test::TempDir tmp;
  const auto inv = test::run_shell("cd '" + tmp.path().string() +
                                   "' && ROCKDD_PROGRESS_SECONDS=0.01 '" + ROCKDD_BINARY + "' " +
                                   kSoftening + " 2>&1");
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  const auto summary = nlohmann::json::parse(
      test::read_text(tmp.path() / "out/uniaxial-compression/summary.json"));
  ASSERT_TRUE(summary["softening"]["reached"].get<bool>());
  const double ended = summary["softening"]["time"].get<double>();
  ASSERT_LT(ended, 0.5 * 10.0) << "the run should end on softening, well before time.end";
  std::vector<std::string> progress;
  std::stringstream lines(inv.output);
  std::string last_line;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("rockdd: step ", 0) == 0) progress.push_back(line);
    last_line = line;
  }
  ASSERT_GE(progress.size(), 5u) << inv.output;
  for (const std::string& line : progress) {
    EXPECT_NE(line.find(" steps/s  ETA "), std::string::npos) << line;
    EXPECT_EQ(line.find('\r'), std::string::npos) << line;
  }
  // The last line: done, by the softening measure, with nothing left.
  EXPECT_TRUE(std::regex_search(progress.back(),
                                std::regex("  100\\.0% done  softened (7[0-9]|[89][0-9])% of 70%")))
      << progress.back();
  EXPECT_NE(progress.back().find("ETA 00:00:00"), std::string::npos) << progress.back();
  EXPECT_EQ(last_line.rfind("rockdd: ok: ", 0), 0u) << inv.output;
  EXPECT_NE(last_line.find("ended on softening"), std::string::npos) << last_line;
  // The fraction never goes back.
  double before = -1;
  for (const std::string& line : progress) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(line, m, std::regex("  ([0-9.]+)% done")));
    const double fraction = std::stod(m[1]);
    EXPECT_GE(fraction, before) << line;
    before = fraction;
  }
  // More lines than the eleven tenths: the time-driven ones.
  EXPECT_GT(progress.size(), 11u) << inv.output;
}

TEST(CommandLine, ProgressOnATerminalEndsItsLineBeforeTheNextMessage) {
  if (test::run_shell("command -v script >/dev/null").exit_code != 0)
    GTEST_SKIP() << "no script(1) to give rockdd a terminal";
  test::TempDir tmp;
  // script(1) runs rockdd on a pseudo-terminal: stderr is a tty, the line is rewritten.
  const auto inv = test::run_shell("cd '" + tmp.path().string() + "' && script -qec \"'" +
                                   ROCKDD_BINARY + "' " + kSoftening + "\" /dev/null");
  ASSERT_EQ(inv.exit_code, 0) << inv.output;
  const std::size_t ok = inv.output.find("rockdd: ok: ");
  ASSERT_NE(ok, std::string::npos) << inv.output;
  const std::size_t bar = inv.output.rfind("\r[", ok);
  ASSERT_NE(bar, std::string::npos) << "no progress bar on the terminal:\n" << inv.output;
  const std::string last = inv.output.substr(bar, ok - bar);
  EXPECT_NE(last.find("100.0%"), std::string::npos) << last;
  EXPECT_NE(last.find("ETA 00:00:00"), std::string::npos) << last;
  // The message starts a line of its own: the bar's line ended with a newline.
  EXPECT_TRUE(ok > 0 && inv.output[ok - 1] == '\n') << last;
}

}  // namespace
}  // namespace rockdd

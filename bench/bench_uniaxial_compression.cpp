// The paper's uniaxial compression run (data/uniaxial_compression.toml: 8,100 elements,
// Weibull m = 1.5, platen at 0.02 mm/s) from the first step to 20 % post-peak softening
// (time.stop_at_softening = 0.2), on 1 and 2 threads, with and without factor updates
// ([solver] factor_updates: damage passes and spring switches folded into the factor), one
// run per repetition. Counters: the run's steps, damage iterations and open-close iterations,
// each per second of wall time; the share of the wall time in each of the engine's timers
// (summary.json "timers"); the numeric factorizations, those forced by the updated factor's
// solve check, and the damage stage's time per element and pass; the peak stress (MPa) and
// where the run stopped. Outputs are not written (RunOptions::write_outputs).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "bench/bench_main.hpp"
#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"

namespace rockdd {
namespace {

void BM_UniaxialCompressionTo20PercentSoftening(benchmark::State& state) {
  const Scene scene =
      load_scene(std::filesystem::path(ROCKDD_SOURCE_DIR) / "data/uniaxial_compression.toml",
                 {"time.stop_at_softening=0.2", std::string("solver.factor_updates=") +
                                                    (state.range(1) != 0 ? "true" : "false")});
  const Model model = build_scene_model(scene);  // meshing and draws are not timed
  nlohmann::json summary;
  for (auto _ : state) {
    Simulation sim(scene, model);
    RunOptions options;
    options.threads = static_cast<int>(state.range(0));
    options.write_outputs = false;
    const RunResult result = sim.run(options);
    if (!result.ok) {
      state.SkipWithError(result.reason.c_str());
      return;
    }
    summary = result.summary;
  }
  const double wall = summary.at("wall_seconds").get<double>();
  auto count = [&](const char* key) { return summary.at(key).get<double>(); };
  state.counters["steps"] = count("steps");
  state.counters["steps_per_s"] = count("steps") / wall;
  state.counters["damage_it_per_s"] = count("damage_iterations") / wall;
  state.counters["open_close_per_s"] = count("open_close_iterations") / wall;
  for (const char* timer :
       {"assembly", "factorization", "solve", "contact", "damage", "detachment"})
    state.counters[std::string("share_") + timer] =
        summary.at("timers").at(timer).get<double>() / wall;
  state.counters["peak_MPa"] = summary.at("softening").at("peak").get<double>() / 0.075 / 1e6;
  state.counters["stop_time_s"] = summary.at("softening").at("time").get<double>();
  state.counters["blocks"] = count("blocks");
  state.counters["factorizations"] = summary.at("solver").at("factorizations").get<double>();
  state.counters["folded_passes"] = count("folded_damage_passes");
  // Updated factors whose solve failed the backward-error check, and so were refactorized.
  state.counters["refactorized_by_check"] = count("untrusted_updated_solves");
  // The damage stage alone (laws and onset searches), per element and pass over the elements.
  state.counters["damage_ns_per_element_pass"] = 1e9 *
                                                 summary.at("timers").at("damage").get<double>() /
                                                 (count("damage_stage_passes") * count("elements"));
}

BENCHMARK(BM_UniaxialCompressionTo20PercentSoftening)
    ->ArgNames({"threads", "factor_updates"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Iterations(1)
    ->Repetitions(3)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

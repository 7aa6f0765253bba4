// The damage stage alone (engine/damage/damage_stage) on the paper's uniaxial compression
// (data/uniaxial_compression.toml, seed 1: 8,100 elements), in the state the run reaches at
// t = 1.3 s, just before its peak (a few hundred elements damaged, the rest near their onsets):
// a pass of the laws over every element (DamageStage::evaluate, with and without starting
// onsets) and the search for the step's first onset along the straight path from the state one
// step earlier (DamageStage::locate_onset). Items are elements: items_per_second is the inverse
// of the time per element and pass. The state repeats: a pass after the first changes nothing.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_main.hpp"
#include "engine/damage/damage_stage.hpp"
#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"

namespace rockdd {
namespace {

/// The scene, its model at the captured step, and that step's start (strain and stress).
struct CapturedState {
  Scene scene;
  Model model;
  std::vector<double> strain0, stress0;
};

const CapturedState& captured() {
  static const CapturedState state = [] {
    CapturedState s{
        load_scene(std::filesystem::path(ROCKDD_SOURCE_DIR) / "data/uniaxial_compression.toml",
                   {"time.end=1.3"}),
        Model{},
        {},
        {}};
    const Model built = build_scene_model(s.scene);
    Simulation sim(s.scene, built);
    RunOptions options;
    options.threads = 1;
    options.write_outputs = false;
    options.on_step = [&](const StepReport&, const Model& model) {
      s.strain0 = s.model.strain;
      s.stress0 = s.model.stress;
      s.model = model;
    };
    sim.run(options);
    return s;
  }();
  return state;
}

void BM_DamagePass(benchmark::State& state) {
  const CapturedState& s = captured();
  Model model = s.model;
  DamageStage stage(s.scene, model);
  const bool start_onsets = state.range(0) != 0;
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(1)));
  stage.evaluate(model, s.scene.fracture.damage_band, start_onsets);  // the state repeats after
  for (auto _ : state) {
    const DamageChange change = stage.evaluate(model, s.scene.fracture.damage_band, start_onsets);
    benchmark::DoNotOptimize(change);
  }
  state.SetItemsProcessed(state.iterations() * model.num_elements());
}
BENCHMARK(BM_DamagePass)
    ->ArgNames({"start_onsets", "threads"})
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->Unit(benchmark::kMicrosecond);

void BM_LocateOnset(benchmark::State& state) {
  const CapturedState& s = captured();
  const DamageStage stage(s.scene, s.model);
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    const OnsetSearch search = stage.locate_onset(s.model, s.strain0, s.stress0, 1.0);
    benchmark::DoNotOptimize(search);
  }
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
}
BENCHMARK(BM_LocateOnset)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

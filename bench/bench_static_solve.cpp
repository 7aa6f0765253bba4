// One full static solve of the paper's Brazilian disk through the engine (BCs, loads,
// pattern, colouring, analysis, assembly, factorization, solve, stress recovery) against a
// bare CHOLMOD analyze + factorize + solve of the same assembled matrix, timed alternately
// in the same benchmark so that machine noise hits both alike.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <chrono>

#include "bench/bench_main.hpp"
#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/engine.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/loading/external_loads.hpp"
#include "engine/report/run_result.hpp"
#include "engine/solver/cholmod_solver.hpp"

namespace rockdd {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_BrazilianStaticSolveVsBareCholmod(benchmark::State& state) {
  const Scene scene =
      load_scene(std::filesystem::path(ROCKDD_SOURCE_DIR) / "data/brazilian_disk_elastic.toml");
  const Model model = build_scene_model(scene);  // meshing is not part of the solve

  // The same matrix and right-hand side for the bare reference.
  const BoundaryConditions bc = build_boundary_conditions(scene, model);
  const ElementColoring coloring = color_elements(model.conn, model.num_nodes());
  const StiffnessLayout layout = build_stiffness_layout(model.conn, model.num_nodes(), bc.equation);
  std::vector<double> values(static_cast<std::size_t>(layout.pattern.nnz()));
  assemble_stiffness(model, coloring, layout, bc.equation, 0.0, values);
  const std::vector<double> loads = build_reference_loads(scene, model);
  std::vector<double> rhs(static_cast<std::size_t>(bc.num_equations)), x(rhs.size());
  for (std::size_t d = 0; d < loads.size(); ++d)
    if (bc.equation[d] >= 0) rhs[bc.equation[d]] = loads[d];

  double engine_total = 0, bare_total = 0;
  RunOptions options;
  options.write_outputs = false;
  options.threads = static_cast<int>(state.range(0));
  // Both sides on the benchmark's threads, the engine's set-up included.
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(options.threads));
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    Simulation sim(scene, model);
    const RunResult result = sim.run(options);
    benchmark::DoNotOptimize(result.ok);
    engine_total += seconds_since(start);

    start = std::chrono::steady_clock::now();
    CholmodSolver bare;
    bare.analyze(layout.pattern);
    bare.factorize(values.data());
    bare.solve(rhs.data(), x.data());
    benchmark::DoNotOptimize(x.data());
    bare_total += seconds_since(start);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["engine_ms"] = 1e3 * engine_total / n;
  state.counters["bare_cholmod_ms"] = 1e3 * bare_total / n;
  state.counters["engine_over_bare"] = engine_total / bare_total;
  state.counters["elements"] = model.num_elements();
  state.counters["equations"] = bc.num_equations;
}

BENCHMARK(BM_BrazilianStaticSolveVsBareCholmod)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

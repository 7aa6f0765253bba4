// CHOLMOD on real 2D CST stiffness matrices (structured meshes, left edge clamped) at about
// 1e4, 1e5 and 1e6 dofs: symbolic analysis, numeric factorization with the analysis reused,
// the bare analyze + factorize + solve, and a solve. GFLOP/s from cholmod_common's flop count.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/solver/cholmod_solver.hpp"
#include "structured_mesh.hpp"

namespace rockdd {
namespace {

/// An assembled stiffness with its right-hand side, built once per size.
struct System {
  StiffnessLayout layout;
  std::vector<double> values, rhs, x;
};

System& system_for(long dofs) {
  static std::map<long, std::unique_ptr<System>> cache;
  auto& slot = cache[dofs];
  if (!slot) {
    const int n = static_cast<int>(std::lround(std::sqrt(dofs / 2.0))) - 1;
    const Scene scene = bench::clamped_scene();
    const Model model = build_model(scene, bench::structured_mesh(n, n));
    const BoundaryConditions bc = build_boundary_conditions(scene, model);
    const ElementColoring coloring = color_elements(model.conn, model.num_nodes());
    slot = std::make_unique<System>();
    slot->layout = build_stiffness_layout(model.conn, model.num_nodes(), bc.equation);
    slot->values.assign(static_cast<std::size_t>(slot->layout.pattern.nnz()), 0.0);
    assemble_stiffness(model, coloring, slot->layout, bc.equation, 0.0, slot->values);
    slot->rhs.assign(static_cast<std::size_t>(bc.num_equations), 1.0);
    slot->x.resize(slot->rhs.size());
  }
  return *slot;
}

void report(benchmark::State& state, const System& s, const SolverStats& stats,
            double flops_per_iteration) {
  state.counters["dofs"] = s.layout.pattern.n;
  state.counters["GFLOP/s"] =
      benchmark::Counter(flops_per_iteration * 1e-9 * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["factor_flops"] = stats.last_factor_flops;
}

void BM_Analyze(benchmark::State& state) {
  System& s = system_for(state.range(0));
  for (auto _ : state) {
    CholmodSolver solver;
    solver.analyze(s.layout.pattern);
  }
  state.counters["dofs"] = s.layout.pattern.n;
}

void BM_Refactorize(benchmark::State& state) {
  System& s = system_for(state.range(0));
  CholmodSolver solver;
  solver.analyze(s.layout.pattern);
  solver.factorize(s.values.data());
  for (auto _ : state) solver.factorize(s.values.data());
  report(state, s, solver.stats(), solver.stats().last_factor_flops);
}

void BM_AnalyzeFactorizeSolve(benchmark::State& state) {
  System& s = system_for(state.range(0));
  SolverStats stats;
  for (auto _ : state) {
    CholmodSolver solver;
    solver.analyze(s.layout.pattern);
    solver.factorize(s.values.data());
    solver.solve(s.rhs.data(), s.x.data());
    stats = solver.stats();
  }
  report(state, s, stats, stats.last_factor_flops);
}

void BM_Solve(benchmark::State& state) {
  System& s = system_for(state.range(0));
  CholmodSolver solver;
  solver.analyze(s.layout.pattern);
  solver.factorize(s.values.data());
  for (auto _ : state) solver.solve(s.rhs.data(), s.x.data());
  state.counters["dofs"] = s.layout.pattern.n;
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(10'000)
      ->Arg(100'000)
      ->Arg(1'000'000)
      ->ArgName("dofs")
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

BENCHMARK(BM_Analyze)->Apply(sizes);
BENCHMARK(BM_Refactorize)->Apply(sizes);
BENCHMARK(BM_AnalyzeFactorizeSolve)->Apply(sizes);
BENCHMARK(BM_Solve)->Apply(sizes);

}  // namespace
}  // namespace rockdd

BENCHMARK_MAIN();

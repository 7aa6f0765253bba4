// CHOLMOD on real 2D CST stiffness matrices (structured meshes, left edge clamped) at about
// 1e4, 1e5 and 1e6 dofs: symbolic analysis, numeric factorization with the analysis reused,
// the bare analyze + factorize + solve, and a solve, for each fill-reducing ordering. GFLOP/s
// from cholmod_common's flop count.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "bench/bench_main.hpp"
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
  std::vector<double> equation_xy;  // x and y of each equation's node
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
    slot->equation_xy = equation_positions(model.X, bc.equation, bc.num_equations);
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

/// The ordering of a benchmark's second argument.
FillOrdering ordering_arg(const benchmark::State& state) {
  return static_cast<FillOrdering>(state.range(1));
}

void report_analysis(benchmark::State& state, const System& s, const SolverStats& stats) {
  state.counters["dofs"] = s.layout.pattern.n;
  state.counters["factor_nonzeros"] = stats.factor_nonzeros;
  state.counters["predicted_flops"] = stats.analysis_flops;
  state.SetLabel(std::string(fill_ordering_name(ordering_arg(state))));
}

/// The symbolic analysis alone, with CHOLMOD's own ordering of the dof graph (ordering 0:
/// AMD, then METIS where AMD fills badly; the old default) against the node strategy (3:
/// CHOLMOD's AMD, then the dissection by coordinates where AMD's factor is costly and METIS
/// of the node graph where AMD fills badly, as for a system factorized many times) and the
/// orderings of the node graph alone (1: METIS, 2: AMD, 5: the dissection by coordinates)
/// given to CHOLMOD. Every analysis is given the nodes' coordinates.
void BM_Analyze(benchmark::State& state) {
  System& s = system_for(state.range(0));
  SolverStats stats;
  for (auto _ : state) {
    CholmodSolver solver(ordering_arg(state));
    solver.analyze(s.layout.pattern, s.equation_xy);
    stats = solver.stats();
  }
  report_analysis(state, s, stats);
}

void BM_Refactorize(benchmark::State& state) {
  System& s = system_for(state.range(0));
  CholmodSolver solver(ordering_arg(state));
  solver.analyze(s.layout.pattern, s.equation_xy);
  solver.factorize(s.values.data());
  for (auto _ : state) solver.factorize(s.values.data());
  report(state, s, solver.stats(), solver.stats().last_factor_flops);
  report_analysis(state, s, solver.stats());
}

void BM_AnalyzeFactorizeSolve(benchmark::State& state) {
  System& s = system_for(state.range(0));
  SolverStats stats;
  for (auto _ : state) {
    CholmodSolver solver(ordering_arg(state));
    solver.analyze(s.layout.pattern, s.equation_xy);
    solver.factorize(s.values.data());
    solver.solve(s.rhs.data(), s.x.data());
    stats = solver.stats();
  }
  report(state, s, stats, stats.last_factor_flops);
  report_analysis(state, s, stats);
}

void BM_Solve(benchmark::State& state) {
  System& s = system_for(state.range(0));
  CholmodSolver solver(ordering_arg(state));
  solver.analyze(s.layout.pattern, s.equation_xy);
  solver.factorize(s.values.data());
  for (auto _ : state) solver.solve(s.rhs.data(), s.x.data());
  state.counters["dofs"] = s.layout.pattern.n;
  state.SetLabel(std::string(fill_ordering_name(ordering_arg(state))));
}

/// k right-hand sides in one pass over the factor (the node strategy): what a capacitance
/// (Woodbury) solve of a damage pass whose change has k columns pays for A^{-1} U before it
/// saves a refactorization. Compare seconds_per_column with BM_Refactorize at the same size.
void BM_SolveColumns(benchmark::State& state) {
  System& s = system_for(state.range(0));
  const auto columns = static_cast<int>(state.range(1));
  CholmodSolver solver(FillOrdering::node);
  solver.analyze(s.layout.pattern, s.equation_xy);
  solver.factorize(s.values.data());
  std::vector<double> b(s.rhs.size() * static_cast<std::size_t>(columns), 1.0), x(b.size());
  for (auto _ : state) solver.solve(b.data(), x.data(), columns);
  state.counters["dofs"] = s.layout.pattern.n;
  state.counters["columns"] = columns;
  // Columns per second, inverted: seconds per column.
  state.counters["seconds_per_column"] =
      benchmark::Counter(static_cast<double>(columns) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// Sizes by orderings (FillOrdering: 0 CHOLMOD's own, the old default; 3 the node strategy,
/// the new default; 1 METIS, 2 AMD and 5 the dissection by coordinates of the node graph).
void sizes(benchmark::internal::Benchmark* b) {
  b->ArgsProduct({{10'000, 100'000, 1'000'000}, {0, 3, 1, 2, 5}})
      ->ArgNames({"dofs", "ordering"})
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

BENCHMARK(BM_Analyze)->Apply(sizes);
BENCHMARK(BM_Refactorize)->Apply(sizes);
BENCHMARK(BM_AnalyzeFactorizeSolve)->Apply(sizes);
BENCHMARK(BM_Solve)->Apply(sizes);
BENCHMARK(BM_SolveColumns)
    ->ArgsProduct({{10'000, 100'000}, {1, 8, 32, 96}})
    ->ArgNames({"dofs", "columns"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

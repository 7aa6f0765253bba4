// Assembly throughput (elements/s) of the stiffness into its fixed pattern, and of the
// internal force, at 1e4, 1e5 and 1e6 elements on 1 and 2 threads.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <map>
#include <memory>

#include "bench/bench_main.hpp"
#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/internal_force.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "structured_mesh.hpp"

namespace rockdd {
namespace {

/// Everything assembly needs, built once per size and shared by the benchmarks.
struct Setup {
  Model model;
  BoundaryConditions bc;
  ElementColoring coloring;
  StiffnessLayout layout;
  std::vector<double> values;
};

Setup& setup_for(long elements) {
  static std::map<long, std::unique_ptr<Setup>> cache;
  auto& slot = cache[elements];
  if (!slot) {
    const int n = static_cast<int>(std::lround(std::sqrt(elements / 2.0)));
    const Scene scene = bench::clamped_scene();
    slot = std::make_unique<Setup>();
    slot->model = build_model(scene, bench::structured_mesh(n, n));
    slot->bc = build_boundary_conditions(scene, slot->model);
    slot->coloring = color_elements(slot->model.conn, slot->model.num_nodes());
    slot->layout =
        build_stiffness_layout(slot->model.conn, slot->model.num_nodes(), slot->bc.equation);
    slot->values.assign(static_cast<std::size_t>(slot->layout.pattern.nnz()), 0.0);
  }
  return *slot;
}

void BM_AssembleStiffness(benchmark::State& state) {
  Setup& s = setup_for(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  for (auto _ : state) {
    assemble_stiffness(s.model, s.coloring, s.layout, s.bc.equation, 0.0, s.values);
    benchmark::DoNotOptimize(s.values.data());
  }
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
  state.counters["elements"] = s.model.num_elements();
}

void BM_InternalForce(benchmark::State& state) {
  Setup& s = setup_for(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  std::vector<double> u(s.model.X.size()), f(u.size());
  for (std::size_t d = 0; d < u.size(); ++d) u[d] = 1e-6 * std::sin(0.1 * static_cast<double>(d));
  for (auto _ : state) {
    compute_internal_force(s.model, s.coloring, u, s.model.strain, s.model.stress, f);
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
}

/// The same pass co-rotated, as every quasi-static or dynamic step runs it: each element's
/// rotation is taken out before its strain and put back on its forces.
void BM_InternalForceCorotated(benchmark::State& state) {
  Setup& s = setup_for(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  std::vector<double> u(s.model.X.size()), f(u.size());
  for (std::size_t d = 0; d < u.size(); ++d) u[d] = 1e-6 * std::sin(0.1 * static_cast<double>(d));
  std::vector<double> element_force(6 * static_cast<std::size_t>(s.model.num_elements()));
  for (auto _ : state) {
    compute_internal_force(s.model, s.coloring, u, s.model.strain, s.model.stress, f, true,
                           element_force);
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
}

void BM_StiffnessLayout(benchmark::State& state) {
  Setup& s = setup_for(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        build_stiffness_layout(s.model.conn, s.model.num_nodes(), s.bc.equation));
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
}

void sizes_and_threads(benchmark::internal::Benchmark* b) {
  for (const long elements : {10'000L, 100'000L, 1'000'000L})
    for (const long threads : {1L, 2L}) b->Args({elements, threads});
  b->ArgNames({"elements", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_AssembleStiffness)->Apply(sizes_and_threads);
BENCHMARK(BM_InternalForce)->Apply(sizes_and_threads);
BENCHMARK(BM_InternalForceCorotated)->Apply(sizes_and_threads);
BENCHMARK(BM_StiffnessLayout)->Apply(sizes_and_threads);

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

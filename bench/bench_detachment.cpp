// Fracture's topology rebuild per newly damaged element (METHOD.md "Fracture"), at about 1e4
// and 1e5 elements: structured triangle meshes (71 x 71 and 224 x 224 squares, left edge
// clamped, one damageable body) on which k elements reach damage 0.5 against threshold 0,
// either scattered (k = 1, 10, 100, 1000, a fixed-seed shuffle) or as a crack line (the lower
// triangles of the middle row of squares, one per column, which cuts the mesh in two).
// (1) BM_DetachDamagedElements: detach_damaged_elements alone (edge adjacency, blocks, node
//     split, named sets, lumped masses) on a fresh copy of the damaged, not yet detached model.
// (2) BM_RebuildAfterDetachment: what Simulation::detach_fractured_elements rebuilds after it:
//     the step's 11 node fields follow the split, boundary conditions and reference loads,
//     element colouring, the contact stage (block boundary, contacts carried over from the
//     stage before), the fragment restraint (steps without inertia), the stiffness layout and
//     CHOLMOD's symbolic analysis; `*_ms` counters give each part. Probes and the static
//     free-block check are left out.
// Both whole passes scale with the mesh, not with k: `per_damaged` (seconds per newly damaged
// element) says what one more damaged element costs when it is detached on its own.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "bench/bench_main.hpp"
#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/contact/contact_stage.hpp"
#include "engine/damage/detachment.hpp"
#include "engine/damage/fragment_restraint.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/loading/external_loads.hpp"
#include "engine/model/element_strength.hpp"
#include "engine/solver/cholmod_solver.hpp"
#include "structured_mesh.hpp"

namespace rockdd {
namespace {

/// Node fields of Simulation's step state that follow a split (acceleration, f_int, ...).
constexpr int kStepFields = 11;

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double>(end - start).count();
}

/// clamped_scene() with a damageable rock (tensile strength, friction angle).
Scene damage_scene() {
  Scene scene = bench::clamped_scene();
  scene.materials[0].tensile_strength = 5e6;
  scene.materials[0].friction_angle = 30.0;
  return scene;
}

/// The undamaged model of an n x n structured mesh, built once per size.
const Model& undamaged_model(const Scene& scene, int n) {
  static std::map<int, std::unique_ptr<Model>> cache;
  auto& slot = cache[n];
  if (!slot) {
    slot = std::make_unique<Model>(build_model(scene, bench::structured_mesh(n, n)));
    assign_element_strengths(scene, *slot);
  }
  return *slot;
}

/// The elements to damage: the lower triangle of every square of the middle row (crack), or
/// the first k of a fixed-seed shuffle of all elements.
std::vector<std::int32_t> damaged_elements(int n, std::int32_t num_elements, long k, bool crack) {
  std::vector<std::int32_t> out;
  if (crack) {
    for (int i = 0; i < n; ++i) out.push_back(2 * ((n / 2) * n + i));
    return out;
  }
  out.resize(static_cast<std::size_t>(num_elements));
  std::iota(out.begin(), out.end(), 0);
  std::mt19937 rng(2024);
  std::shuffle(out.begin(), out.end(), rng);
  out.resize(static_cast<std::size_t>(k));
  return out;
}

/// One case: the damaged model before detachment, the model after it, and the contact stage
/// of the undamaged model (the stage a detachment replaces).
struct Case {
  Scene scene = damage_scene();
  Model damaged, detached;
  Detachment detachment;
  std::unique_ptr<ContactStage> before;
  std::vector<double> threshold;
};

/// The case of (elements, k, crack); only the latest is kept (repetitions run back to back).
const Case& case_for(const benchmark::State& state) {
  // As in the engine's process, large blocks stay in the heap (the first CholmodSolver sets
  // that, engine/solver/cholmod_solver.cpp): the detachment then reuses freed memory instead
  // of page-faulting fresh mmapped arrays in.
  static const CholmodSolver heap_policy;
  static std::unique_ptr<Case> cached;
  static std::vector<std::int64_t> cached_key;
  const std::vector<std::int64_t> key = {state.range(0), state.range(1), state.range(2)};
  if (cached && cached_key == key) return *cached;
  cached.reset();
  auto c = std::make_unique<Case>();
  const int n = static_cast<int>(std::lround(std::sqrt(state.range(0) / 2.0)));
  const Model& undamaged = undamaged_model(c->scene, n);
  c->damaged = undamaged;
  for (const std::int32_t e :
       damaged_elements(n, undamaged.num_elements(), state.range(1), state.range(2) != 0))
    c->damaged.damage[e] = 0.5;
  c->threshold.assign(static_cast<std::size_t>(undamaged.num_elements()), 0.0);
  c->detached = c->damaged;
  std::vector<std::uint8_t> detached;
  c->detachment = detach_damaged_elements(c->detached, c->threshold, detached);
  c->before = std::make_unique<ContactStage>(c->scene, undamaged, c->scene.analysis,
                                             c->scene.time.integrator);
  cached = std::move(c);
  cached_key = key;
  return *cached;
}

void report(benchmark::State& state, const Case& c) {
  state.counters["elements"] = c.damaged.num_elements();
  state.counters["damaged"] = c.detachment.detached;
  state.counters["blocks"] = c.detached.num_blocks;
  state.counters["per_damaged"] =
      benchmark::Counter(c.detachment.detached, benchmark::Counter::kIsIterationInvariantRate |
                                                    benchmark::Counter::kInvert);
}

/// detach_damaged_elements on a fresh copy of the damaged model (the copy is not timed).
void BM_DetachDamagedElements(benchmark::State& state) {
  const Case& c = case_for(state);
  for (auto _ : state) {
    Model model = c.damaged;
    std::vector<std::uint8_t> detached;
    const auto start = Clock::now();
    const Detachment d = detach_damaged_elements(model, c.threshold, detached);
    state.SetIterationTime(seconds_between(start, Clock::now()));
    benchmark::DoNotOptimize(d.detached);
  }
  report(state, c);
}

/// What the simulation rebuilds on the detached model, part by part.
void BM_RebuildAfterDetachment(benchmark::State& state) {
  const Case& c = case_for(state);
  const Model& model = c.detached;
  const std::size_t old_dofs = c.damaged.X.size();
  CholmodSolver solver;  // the simulation's solver, analysed again for the new pattern
  double part[7] = {};
  for (auto _ : state) {
    std::vector<std::vector<double>> fields(kStepFields, std::vector<double>(old_dofs, 0.0));
    Clock::time_point t[8];
    t[0] = Clock::now();
    for (auto& field : fields) follow_split_nodes(c.detachment.node_origin, field);
    t[1] = Clock::now();
    const BoundaryConditions bc = build_boundary_conditions(c.scene, model);
    const std::vector<double> loads = build_reference_loads(c.scene, model);
    t[2] = Clock::now();
    const ElementColoring coloring = color_elements(model.conn, model.num_nodes());
    t[3] = Clock::now();
    ContactStage contact(c.scene, model, c.scene.analysis, c.scene.time.integrator);
    std::vector<Contact> committed = c.before->contacts();
    contact.carry_contacts_from(*c.before, committed);
    t[4] = Clock::now();
    const FragmentRestraint fragments(model, bc, 1e-6);
    t[5] = Clock::now();
    std::vector<std::int32_t> conn = model.conn;
    const std::vector<std::int32_t> triples = contact.triples();
    conn.insert(conn.end(), triples.begin(), triples.end());
    const StiffnessLayout layout = build_stiffness_layout(conn, model.num_nodes(), bc.equation);
    t[6] = Clock::now();
    solver.analyze(layout.pattern);
    t[7] = Clock::now();
    state.SetIterationTime(seconds_between(t[0], t[7]));
    for (int p = 0; p < 7; ++p) part[p] += seconds_between(t[p], t[p + 1]);
    benchmark::DoNotOptimize(loads.data());
    benchmark::DoNotOptimize(coloring.chunk.data());
    benchmark::DoNotOptimize(fragments.num_dofs());
  }
  report(state, c);
  const char* names[7] = {"fields_ms",    "bc_loads_ms", "coloring_ms", "contact_ms",
                          "fragments_ms", "layout_ms",   "analyze_ms"};
  for (int p = 0; p < 7; ++p)
    state.counters[names[p]] =
        benchmark::Counter(1e3 * part[p], benchmark::Counter::kAvgIterations);
}

void cases(benchmark::internal::Benchmark* b) {
  for (const long n : {71L, 224L}) {
    for (const long k : {1L, 10L, 100L, 1000L}) b->Args({2 * n * n, k, 0});
    b->Args({2 * n * n, n, 1});
  }
  b->ArgNames({"elements", "damaged", "crack"})->Unit(benchmark::kMillisecond)->UseManualTime();
}

BENCHMARK(BM_DetachDamagedElements)->Apply(cases);
BENCHMARK(BM_RebuildAfterDetachment)->Apply(cases);

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

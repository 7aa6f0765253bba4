// Open-close iterations: what a change of a few contact states costs the solver.
//
// (a) Factor update against refactorization, on real 2D CST stiffness matrices (structured
//     meshes, left edge clamped) at about 1e4, 1e5 and 1e6 dofs: the numeric refactorization
//     with the analysis reused, against cholmod_updown of k random contact-like rank-1 terms
//     (6 dofs over the 3 nodes of a mesh triangle), k = 1, 10, 100, 1000, on a factor that is
//     already simplicial; the first update after a factorization (which converts the factor);
//     a factorization that follows updates; the solve with either form of the factor. Each update
//     counter `break_even_k` is k * refactor / update: the number of such columns that one
//     refactorization buys.
// (b) A pile of 100 x 100 square blocks (2 triangles each, own nodes, bottom row clamped,
//     39,600 vertex-edge contacts between neighbours, DDA mass term), one open-close iteration
//     with ~1 % of the contacts changing state (open / sliding: kn g g^T / locked: + ks t t^T):
//     (i) analyze + factorize + solve, (ii) factorize + solve with the analysis reused,
//     (iii) update + downdate of the factor + solve.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "bench/bench_main.hpp"
#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/solver/cholmod_solver.hpp"
#include "structured_mesh.hpp"

namespace rockdd {
namespace {

constexpr double kYoung = 50e9;
constexpr double kNormalStiffness = 20.0 * kYoung;  // contact_stage's default, 20 E t (t = 1)
constexpr double kShearStiffness = 0.4 * kNormalStiffness;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double relative_difference(const std::vector<double>& x, const std::vector<double>& y) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    num += (x[i] - y[i]) * (x[i] - y[i]);
    den += y[i] * y[i];
  }
  return std::sqrt(num / den);
}

// ---------------------------------------------------------------------------------------------
// (a) Structured meshes.

/// An assembled stiffness with what random contact-like terms are drawn from.
struct MeshSystem {
  StiffnessLayout layout;
  std::vector<std::int32_t> conn, equation;
  std::vector<double> values, rhs, x;
};

MeshSystem& mesh_system(long dofs) {
  static std::map<long, std::unique_ptr<MeshSystem>> cache;
  auto& slot = cache[dofs];
  if (!slot) {
    const int n = static_cast<int>(std::lround(std::sqrt(dofs / 2.0))) - 1;
    const Scene scene = bench::clamped_scene();
    const Model model = build_model(scene, bench::structured_mesh(n, n));
    const BoundaryConditions bc = build_boundary_conditions(scene, model);
    const ElementColoring coloring = color_elements(model.conn, model.num_nodes());
    slot = std::make_unique<MeshSystem>();
    slot->layout = build_stiffness_layout(model.conn, model.num_nodes(), bc.equation);
    slot->values.assign(static_cast<std::size_t>(slot->layout.pattern.nnz()), 0.0);
    assemble_stiffness(model, coloring, slot->layout, bc.equation, 0.0, slot->values);
    slot->conn = model.conn;
    slot->equation = bc.equation;
    slot->rhs.assign(static_cast<std::size_t>(bc.num_equations), 1.0);
    slot->x.resize(slot->rhs.size());
  }
  return *slot;
}

/// k columns sqrt(kn) g, g the gap gradient of a vertex against the opposite side of a random
/// mesh triangle: [n, -(1 - xi) n, -xi n] over its 3 nodes.
LowRankTerms random_contact_terms(const MeshSystem& s, int k, unsigned seed) {
  std::mt19937 rng(seed);
  const auto num_elements = static_cast<std::int32_t>(s.conn.size() / 3);
  std::uniform_int_distribution<std::int32_t> element(0, num_elements - 1);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * 3.141592653589793), xi(0.0, 1.0);
  LowRankTerms terms;
  for (int c = 0; c < k; ++c) {
    const std::int32_t e = element(rng);
    const double a = angle(rng), x = xi(rng), root = std::sqrt(kNormalStiffness);
    const double n[2] = {std::cos(a), std::sin(a)};
    const double weight[3] = {1.0, -(1.0 - x), -x};
    std::int32_t rows[6];
    double values[6];
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 2; ++d) {
        rows[2 * v + d] = s.equation[2 * s.conn[3 * e + v] + d];
        values[2 * v + d] = root * weight[v] * n[d];
      }
    terms.add_column(rows, values);
  }
  return terms;
}

/// A solver on the mesh system, factorized, then turned simplicial by an update and the
/// matching downdate; with the best of two refactorization times.
struct UpdatedSolver {
  CholmodSolver solver;
  double refactor_seconds = 0.0;
};

UpdatedSolver& updated_solver(long dofs) {
  static std::map<long, std::unique_ptr<UpdatedSolver>> cache;
  auto& slot = cache[dofs];
  if (!slot) {
    MeshSystem& s = mesh_system(dofs);
    slot = std::make_unique<UpdatedSolver>();
    slot->solver.analyze(s.layout.pattern);
    slot->solver.factorize(s.values.data());
    slot->solver.factorize(s.values.data());
    slot->refactor_seconds = slot->solver.stats().last_factor_seconds;
    slot->solver.factorize(s.values.data());
    slot->refactor_seconds =
        std::min(slot->refactor_seconds, slot->solver.stats().last_factor_seconds);
    const LowRankTerms one = random_contact_terms(s, 1, 12345);
    slot->solver.update(one, true);
    slot->solver.update(one, false);
  }
  return *slot;
}

void BM_Refactor(benchmark::State& state) {
  MeshSystem& s = mesh_system(state.range(0));
  CholmodSolver solver;
  solver.analyze(s.layout.pattern);
  solver.factorize(s.values.data());
  for (auto _ : state) solver.factorize(s.values.data());
  state.counters["dofs"] = s.layout.pattern.n;
}

void BM_Update(benchmark::State& state) {
  MeshSystem& s = mesh_system(state.range(0));
  UpdatedSolver& u = updated_solver(state.range(0));
  const int k = static_cast<int>(state.range(1));
  const LowRankTerms terms = random_contact_terms(s, k, static_cast<unsigned>(k));
  // Closing then opening the same contacts: the matrix returns to A every second iteration.
  bool add = true;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    u.solver.update(terms, add);
    seconds += seconds_since(start);
    add = !add;
  }
  if (!add) u.solver.update(terms, false);
  const double per_update = seconds / static_cast<double>(state.iterations());
  state.counters["dofs"] = s.layout.pattern.n;
  state.counters["refactor_ms"] = 1e3 * u.refactor_seconds;
  state.counters["break_even_k"] = k * u.refactor_seconds / per_update;
}

/// The first update after a factorization: conversion to simplicial LDL^T + a rank-1 update.
void BM_FirstUpdate(benchmark::State& state) {
  MeshSystem& s = mesh_system(state.range(0));
  CholmodSolver solver;
  solver.analyze(s.layout.pattern);
  const LowRankTerms one = random_contact_terms(s, 1, 777);
  for (auto _ : state) {
    state.PauseTiming();
    solver.factorize(s.values.data());
    state.ResumeTiming();
    solver.update(one, true);
  }
  state.counters["dofs"] = s.layout.pattern.n;
}

/// A factorization that follows updates: the simplicial factor is dropped and the numeric
/// factor rebuilt from a copy of the analysis (against BM_Refactor, which refactorizes a
/// supernodal factor in place).
void BM_RefactorAfterUpdate(benchmark::State& state) {
  MeshSystem& s = mesh_system(state.range(0));
  CholmodSolver solver;
  solver.analyze(s.layout.pattern);
  solver.factorize(s.values.data());
  const LowRankTerms one = random_contact_terms(s, 1, 777);
  for (auto _ : state) {
    state.PauseTiming();
    solver.update(one, true);
    state.ResumeTiming();
    solver.factorize(s.values.data());
  }
  state.counters["dofs"] = s.layout.pattern.n;
}

void BM_SolveSupernodal(benchmark::State& state) {
  MeshSystem& s = mesh_system(state.range(0));
  CholmodSolver solver;
  solver.analyze(s.layout.pattern);
  solver.factorize(s.values.data());
  for (auto _ : state) solver.solve(s.rhs.data(), s.x.data());
  state.counters["dofs"] = s.layout.pattern.n;
}

void BM_SolveSimplicial(benchmark::State& state) {
  MeshSystem& s = mesh_system(state.range(0));
  UpdatedSolver& u = updated_solver(state.range(0));
  for (auto _ : state) u.solver.solve(s.rhs.data(), s.x.data());
  state.counters["dofs"] = s.layout.pattern.n;
}

void mesh_sizes(benchmark::internal::Benchmark* b) {
  for (const long dofs : {10'000L, 100'000L, 1'000'000L}) b->Args({dofs});
  b->ArgNames({"dofs"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

void mesh_sizes_and_ranks(benchmark::internal::Benchmark* b) {
  for (const long dofs : {10'000L, 100'000L, 1'000'000L})
    for (const long k : {1L, 10L, 100L, 1000L}) b->Args({dofs, k});
  b->ArgNames({"dofs", "k"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_Refactor)->Apply(mesh_sizes);
BENCHMARK(BM_Update)->Apply(mesh_sizes_and_ranks);
BENCHMARK(BM_FirstUpdate)->Apply(mesh_sizes);
BENCHMARK(BM_RefactorAfterUpdate)->Apply(mesh_sizes);
BENCHMARK(BM_SolveSupernodal)->Apply(mesh_sizes);
BENCHMARK(BM_SolveSimplicial)->Apply(mesh_sizes);

// ---------------------------------------------------------------------------------------------
// (b) A pile of blocks.

enum class ContactState : std::uint8_t { open, sliding, locked };

/// A vertex-edge contact: nodes (vertex, a, b), gap gradient g and slip gradient t over them.
struct PileContact {
  std::int32_t nodes[3];
  double g[6], t[6];
};

/// One iteration's state changes: (contact, from, to).
struct Change {
  std::int32_t contact;
  ContactState from, to;
};

struct Pile {
  static constexpr int kSide = 100;  // blocks per row and per column
  static constexpr int kCycle = 32;  // iterations forward, then the same undone
  Model model;
  BoundaryConditions bc;
  StiffnessLayout layout;  // elements, then one 3-node element per contact
  std::vector<PileContact> contacts;
  std::vector<ContactState> initial;
  std::vector<double> initial_values, rhs;
  std::map<int, std::vector<std::vector<Change>>> cycles;  // by changes per iteration

  std::int32_t contact_slot(std::size_t c) const {
    return model.num_elements() + static_cast<std::int32_t>(c);
  }

  /// values += sign * (state's springs) of contact c, through the contact element's scatter.
  void scatter(std::size_t c, ContactState s, double sign, std::vector<double>& values) const {
    if (s == ContactState::open) return;
    const PileContact& pc = contacts[c];
    const std::int32_t* to =
        &layout.scatter[static_cast<std::size_t>(contact_slot(c)) * kElementUpperEntries];
    for (int a = 0; a < 6; ++a)
      for (int b = a; b < 6; ++b, ++to) {
        if (*to < 0) continue;
        double k = kNormalStiffness * pc.g[a] * pc.g[b];
        if (s == ContactState::locked) k += kShearStiffness * pc.t[a] * pc.t[b];
        values[*to] += sign * k;
      }
  }

  /// The columns that go from `from` to `to`: added to `close`, removed to `open`.
  void columns(std::size_t c, ContactState from, ContactState to, LowRankTerms& close,
               LowRankTerms& open) const {
    const PileContact& pc = contacts[c];
    std::int32_t rows[6];
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 2; ++d) rows[2 * v + d] = bc.equation[2 * pc.nodes[v] + d];
    auto column = [&](const double* vec, double stiffness, LowRankTerms& terms) {
      double values[6];
      const double root = std::sqrt(stiffness);
      for (int i = 0; i < 6; ++i) values[i] = root * vec[i];
      terms.add_column(rows, values);
    };
    const bool normal_before = from != ContactState::open, normal_after = to != ContactState::open;
    const bool shear_before = from == ContactState::locked,
               shear_after = to == ContactState::locked;
    if (normal_before != normal_after) column(pc.g, kNormalStiffness, normal_after ? close : open);
    if (shear_before != shear_after) column(pc.t, kShearStiffness, shear_after ? close : open);
  }

  /// A cycle of iterations, each changing `changes` random contacts to another state, that
  /// ends where it began (the first half undone in reverse), so benchmarks can loop on it.
  const std::vector<std::vector<Change>>& cycle(int changes) {
    auto& out = cycles[changes];
    if (!out.empty()) return out;
    std::mt19937 rng(static_cast<unsigned>(changes));
    std::uniform_int_distribution<std::int32_t> pick(
        0, static_cast<std::int32_t>(contacts.size()) - 1);
    std::uniform_int_distribution<int> shift(1, 2);
    std::vector<ContactState> state = initial;
    for (int it = 0; it < kCycle; ++it) {
      std::vector<Change> step;
      std::vector<std::uint8_t> taken(contacts.size(), 0);
      while (static_cast<int>(step.size()) < changes) {
        const std::int32_t c = pick(rng);
        if (taken[c]) continue;
        taken[c] = 1;
        const auto to = static_cast<ContactState>((static_cast<int>(state[c]) + shift(rng)) % 3);
        step.push_back({c, state[c], to});
        state[c] = to;
      }
      out.push_back(std::move(step));
    }
    for (int it = kCycle - 1; it >= 0; --it) {
      std::vector<Change> back;
      for (const Change& ch : out[it]) back.push_back({ch.contact, ch.to, ch.from});
      out.push_back(std::move(back));
    }
    return out;
  }

  void apply_to_values(const std::vector<Change>& step, std::vector<double>& values) const {
    for (const Change& ch : step) {
      scatter(static_cast<std::size_t>(ch.contact), ch.from, -1.0, values);
      scatter(static_cast<std::size_t>(ch.contact), ch.to, 1.0, values);
    }
  }

  void update_factor(const std::vector<Change>& step, CholmodSolver& solver, LowRankTerms& close,
                     LowRankTerms& open) const {
    close.clear();
    open.clear();
    for (const Change& ch : step)
      columns(static_cast<std::size_t>(ch.contact), ch.from, ch.to, close, open);
    solver.update(close, true);
    solver.update(open, false);
  }
};

/// Square blocks of side h, own nodes (BL, BR, TR, TL), triangles (BL, BR, TR), (BL, TR, TL);
/// the bottom edges of the bottom row form the clamped curve.
Mesh pile_mesh(int side, double h) {
  Mesh mesh;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const auto base = static_cast<std::int32_t>(mesh.xy.size() / 2);
      constexpr int kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (const auto& [dx, dy] : kCorner) {
        mesh.xy.push_back((i + dx) * h);
        mesh.xy.push_back((j + dy) * h);
      }
      for (const int k : {0, 1, 2, 0, 2, 3}) mesh.triangles.push_back(base + k);
      if (j == 0) mesh.curves["bottom"].push_back({base, base + 1});
    }
  mesh.element_surface.assign(mesh.triangles.size() / 3, 0);
  mesh.surface_body = {"rock"};
  return mesh;
}

Pile& pile() {
  static std::unique_ptr<Pile> cached;
  if (cached) return *cached;
  auto p = std::make_unique<Pile>();
  const int side = Pile::kSide;
  const double h = 0.1;
  Scene scene = bench::clamped_scene();
  scene.boundaries[0].on = "bottom";
  p->model = build_model(scene, pile_mesh(side, h));
  p->bc = build_boundary_conditions(scene, p->model);
  const Model& m = p->model;
  // Corners of block b from its two triangles: BL, BR, TR, TL.
  auto corner = [&](int i, int j, int k) {
    const std::int32_t e = 2 * (j * side + i);
    const int slot[4] = {0, 1, 2, 5};
    return m.conn[3 * e + slot[k]];
  };
  // Two contacts per shared side: the near corners of the right (upper) block against the
  // facing side of the left (lower) block, as if the rows were slightly staggered.
  auto add_contact = [&](std::int32_t vertex, std::int32_t a, std::int32_t b, double xi,
                         const double n[2]) {
    PileContact c{{vertex, a, b}, {}, {}};
    const double s[2] = {-n[1], n[0]};
    const double weight[3] = {1.0, -(1.0 - xi), -xi};
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 2; ++d) {
        c.g[2 * v + d] = weight[v] * n[d];
        c.t[2 * v + d] = weight[v] * s[d];
      }
    p->contacts.push_back(c);
  };
  const double right[2] = {1.0, 0.0}, up[2] = {0.0, 1.0};
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      if (i + 1 < side) {  // right side of (i, j): BR -> TR, against BL, TL of (i + 1, j)
        add_contact(corner(i + 1, j, 0), corner(i, j, 1), corner(i, j, 2), 0.1, right);
        add_contact(corner(i + 1, j, 3), corner(i, j, 1), corner(i, j, 2), 0.9, right);
      }
      if (j + 1 < side) {  // top of (i, j): TL -> TR, against BL, BR of (i, j + 1)
        add_contact(corner(i, j + 1, 0), corner(i, j, 3), corner(i, j, 2), 0.1, up);
        add_contact(corner(i, j + 1, 1), corner(i, j, 3), corner(i, j, 2), 0.9, up);
      }
    }
  std::vector<std::int32_t> conn = m.conn;
  for (const PileContact& c : p->contacts) conn.insert(conn.end(), c.nodes, c.nodes + 3);
  p->layout = build_stiffness_layout(conn, m.num_nodes(), p->bc.equation);
  const ElementColoring coloring = color_elements(m.conn, m.num_nodes());
  p->initial_values.assign(static_cast<std::size_t>(p->layout.pattern.nnz()), 0.0);
  const double dt = 1e-3;  // DDA inertia: 2 / dt^2 times the lumped mass on the diagonal
  assemble_stiffness(m, coloring, p->layout, p->bc.equation, 2.0 / (dt * dt), p->initial_values);
  // Contacts start 20 % open, 40 % sliding, 40 % locked.
  std::mt19937 rng(2024);
  std::discrete_distribution<int> draw({20.0, 40.0, 40.0});
  for (std::size_t c = 0; c < p->contacts.size(); ++c) {
    p->initial.push_back(static_cast<ContactState>(draw(rng)));
    p->scatter(c, p->initial.back(), 1.0, p->initial_values);
  }
  p->rhs.assign(static_cast<std::size_t>(p->bc.num_equations), 0.0);
  for (std::int32_t n = 0; n < m.num_nodes(); ++n)  // gravity
    if (const std::int32_t eq = p->bc.equation[2 * n + 1]; eq >= 0)
      p->rhs[eq] = -10.0 * m.node_mass[n];

  // The update path and the refactorization path agree after one iteration.
  const auto& step = p->cycle(400)[0];
  std::vector<double> values = p->initial_values, x_refactor(p->rhs.size()),
                      x_update(p->rhs.size());
  CholmodSolver a, b;
  a.analyze(p->layout.pattern);
  b.analyze(p->layout.pattern);
  b.factorize(values.data());
  p->apply_to_values(step, values);
  a.factorize(values.data());
  a.solve(p->rhs.data(), x_refactor.data());
  LowRankTerms close, open;
  p->update_factor(step, b, close, open);
  b.solve(p->rhs.data(), x_update.data());
  const double diff = relative_difference(x_update, x_refactor);
  std::fprintf(stderr,
               "pile: %d blocks, %d elements, %zu contacts, %d equations, nnz(A) %lld; "
               "update vs refactor: relative difference %.1e\n",
               side * side, m.num_elements(), p->contacts.size(), p->bc.num_equations,
               static_cast<long long>(p->layout.pattern.nnz()), diff);
  if (!(diff < 1e-8)) {
    std::fprintf(stderr, "pile: the update does not reproduce the refactorization\n");
    std::abort();
  }
  cached = std::move(p);
  return *cached;
}

void pile_counters(benchmark::State& state, const Pile& p, int changes) {
  state.counters["dofs"] = p.bc.num_equations;
  state.counters["contacts"] = static_cast<double>(p.contacts.size());
  state.counters["changed"] = changes;
}

/// The symbolic analysis alone: what (ii) saves against (i).
void BM_PileAnalyze(benchmark::State& state) {
  Pile& p = pile();
  for (auto _ : state) {
    CholmodSolver solver;
    solver.analyze(p.layout.pattern);
  }
  state.counters["dofs"] = p.bc.num_equations;
}

/// (i) Every iteration analyses, factorizes and solves from scratch.
void BM_PileAnalyzeFactorizeSolve(benchmark::State& state) {
  Pile& p = pile();
  const int changes = static_cast<int>(state.range(0));
  const auto& cycle = p.cycle(changes);
  std::vector<double> values = p.initial_values, x(p.rhs.size());
  std::size_t it = 0;
  for (auto _ : state) {
    p.apply_to_values(cycle[it++ % cycle.size()], values);
    CholmodSolver solver;
    solver.analyze(p.layout.pattern);
    solver.factorize(values.data());
    solver.solve(p.rhs.data(), x.data());
  }
  pile_counters(state, p, changes);
}

/// (ii) The analysis is reused: factorize and solve.
void BM_PileFactorizeSolve(benchmark::State& state) {
  Pile& p = pile();
  const int changes = static_cast<int>(state.range(0));
  const auto& cycle = p.cycle(changes);
  std::vector<double> values = p.initial_values, x(p.rhs.size());
  CholmodSolver solver;
  solver.analyze(p.layout.pattern);
  std::size_t it = 0;
  for (auto _ : state) {
    p.apply_to_values(cycle[it++ % cycle.size()], values);
    solver.factorize(values.data());
    solver.solve(p.rhs.data(), x.data());
  }
  pile_counters(state, p, changes);
  state.counters["factor_flops"] = solver.stats().last_factor_flops;
}

/// (iii) The factor is updated (closing contacts) and downdated (opening ones), then solved.
/// Steady state: the factor is already simplicial (see BM_PileFirstUpdateSolve).
void BM_PileUpdateSolve(benchmark::State& state) {
  Pile& p = pile();
  const int changes = static_cast<int>(state.range(0));
  const auto& cycle = p.cycle(changes);
  std::vector<double> x(p.rhs.size());
  CholmodSolver solver;
  solver.analyze(p.layout.pattern);
  solver.factorize(p.initial_values.data());
  LowRankTerms close, open;
  p.update_factor(cycle[0], solver, close, open);  // the conversion, outside the timing
  const std::int64_t columns_before = solver.stats().updated_columns;
  std::size_t it = 1;
  for (auto _ : state) {
    p.update_factor(cycle[it++ % cycle.size()], solver, close, open);
    solver.solve(p.rhs.data(), x.data());
  }
  pile_counters(state, p, changes);
  state.counters["rank"] =
      benchmark::Counter(static_cast<double>(solver.stats().updated_columns - columns_before),
                         benchmark::Counter::kAvgIterations);
}

/// The first iteration after a factorization: conversion to simplicial, update, solve.
void BM_PileFirstUpdateSolve(benchmark::State& state) {
  Pile& p = pile();
  const int changes = static_cast<int>(state.range(0));
  const auto& cycle = p.cycle(changes);
  std::vector<double> x(p.rhs.size());
  CholmodSolver solver;
  solver.analyze(p.layout.pattern);
  LowRankTerms close, open;
  for (auto _ : state) {
    state.PauseTiming();
    solver.factorize(p.initial_values.data());
    state.ResumeTiming();
    p.update_factor(cycle[0], solver, close, open);
    solver.solve(p.rhs.data(), x.data());
  }
  pile_counters(state, p, changes);
}

void pile_changes(benchmark::internal::Benchmark* b) {
  // 0.025 %, 0.1 %, 0.25 % and 1 % of the 39,600 contacts change state in each iteration.
  for (const long changes : {10L, 40L, 100L, 400L}) b->Args({changes});
  b->ArgNames({"changed"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_PileAnalyze)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PileAnalyzeFactorizeSolve)->Apply(pile_changes);
BENCHMARK(BM_PileFactorizeSolve)->Apply(pile_changes);
BENCHMARK(BM_PileUpdateSolve)->Apply(pile_changes);
BENCHMARK(BM_PileFirstUpdateSolve)->Apply(pile_changes);

}  // namespace
}  // namespace rockdd

int main(int argc, char** argv) {
  return rockdd::bench::run_benchmarks(argc, argv);
}

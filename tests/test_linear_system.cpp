// LinearSystem follows the model's damage: a change of a few elements' moduli is folded into
// the factor by low-rank updates (docs/benchmarks.md, "Damage passes folded into the factor"),
// across damage passes, attempts taken back and steps alike, and every solve with an updated
// factor is checked against the assembled matrix by its normwise backward error
// |b - A x|inf / (max|A| |x|inf + |b|inf). Reference: the same system assembled and factorized
// afresh (CHOLMOD's supernodal LL^T), whose backward error is round-off (< 1e-14 here).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "engine/assembly/element_coloring.hpp"
#include "engine/engine.hpp"
#include "engine/solver/linear_system.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

/// A 2 m x 1 m plate of 1,600 triangles (about 1,700 equations: folding 3 elements, 9 update
/// columns, costs less than a factorization), its left edge fixed, and a right-hand side.
struct Plate {
  Model model;
  ElementColoring coloring;
  std::vector<std::int32_t> equation;
  std::int32_t num_equations = 0;
  std::vector<double> rhs;
};

Plate make_plate() {
  test::TempDir dir;
  const std::string text = test::scene_table("linear-system", "static", "plane = \"stress\"\n") +
                           test::rectangle_mesh(2.0, 1.0, 0.05) +
                           test::material("*", 2500.0, 30e9, 0.25) + test::fixed("left");
  Plate p{build_scene_model(test::scene_from_text(text, dir.path())), {}, {}, 0, {}};
  p.equation.assign(p.model.X.size(), 0);
  std::vector<std::uint8_t> fixed(p.model.X.size(), 0);
  for (const std::int32_t node : p.model.sets.curve_edges["left"])
    for (int c = 0; c < 2; ++c) fixed[2 * static_cast<std::size_t>(node) + c] = 1;
  for (std::size_t d = 0; d < p.equation.size(); ++d)
    p.equation[d] = fixed[d] ? -1 : p.num_equations++;
  p.coloring = color_elements(p.model.conn, p.model.num_nodes());
  p.rhs.resize(static_cast<std::size_t>(p.num_equations));
  for (std::size_t i = 0; i < p.rhs.size(); ++i)
    p.rhs[i] = 1e3 * std::sin(0.37 * static_cast<double>(i) + 0.1);
  return p;
}

/// The solution of the plate's system at its model's damage.
std::vector<double> solve(LinearSystem& system, Plate& plate) {
  system.prepare(plate.model, plate.coloring, plate.equation, 0.0, {});
  std::vector<double> x = plate.rhs;
  system.solve(x);
  return x;
}

/// A freshly assembled and factorized system of the plate.
std::unique_ptr<LinearSystem> fresh_system(StageTimers& timers, const Plate& plate,
                                           bool factor_updates) {
  auto system = std::make_unique<LinearSystem>(timers, std::nullopt, factor_updates);
  system->rebuild(plate.model.conn, plate.model.num_nodes(), plate.equation, plate.num_equations,
                  false);
  return system;
}

/// The plate's solution by a freshly assembled and factorized system.
std::vector<double> fresh_solution(Plate& plate) {
  StageTimers timers;
  auto system = fresh_system(timers, plate, false);
  return solve(*system, plate);
}

/// max |x - y| / max |y|.
double relative_difference(const std::vector<double>& x, const std::vector<double>& y) {
  double difference = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    difference = std::max(difference, std::abs(x[i] - y[i]));
    largest = std::max(largest, std::abs(y[i]));
  }
  return difference / largest;
}

TEST(LinearSystem, DamageOfAFewElementsIsFoldedIntoTheFactorAndSolvesAsAFreshFactor) {
  StageTimers timers;
  Plate plate = make_plate();
  auto system = fresh_system(timers, plate, true);
  const std::vector<double> undamaged = solve(*system, plate);
  EXPECT_EQ(system->solver_stats().factorizations, 1);

  // A damage pass: three elements soften.
  for (const std::int32_t e : {3, 17, 42}) plate.model.damage[e] = 0.6;
  const std::vector<double> damaged = solve(*system, plate);
  EXPECT_EQ(system->stats().folded_damage_passes, 1);
  EXPECT_EQ(system->solver_stats().factorizations, 1);  // updated, not refactorized
  EXPECT_EQ(system->stats().untrusted_updated_solves, 0);
  // An updated factor's answer agrees with a fresh one to its checked backward error (the
  // plate's condition number ~1e3 turns 1e-13 of backward error into ~1e-10 of answer).
  EXPECT_LT(relative_difference(damaged, fresh_solution(plate)), 1e-9);
  EXPECT_GT(relative_difference(damaged, undamaged), 1e-3);  // the change is not round-off

  // An attempt taken back: the damage returns to where it was, and so does the answer.
  std::fill(plate.model.damage.begin(), plate.model.damage.end(), 0.0);
  EXPECT_LT(relative_difference(solve(*system, plate), undamaged), 1e-9);
  EXPECT_EQ(system->stats().folded_damage_passes, 2);
  EXPECT_EQ(system->solver_stats().factorizations, 1);

  // Unchanged damage: nothing to fold, nothing to factorize.
  solve(*system, plate);
  EXPECT_EQ(system->stats().folded_damage_passes, 2);
  EXPECT_EQ(system->solver_stats().factorizations, 1);
}

TEST(LinearSystem, SolveCheckThatFailsRefactorizesAndSolvesAfresh) {
  // A trusted backward error of 0 fails every solve with an updated factor (its residual is
  // never exactly zero): the matrix is refactorized from the assembled values, the answer is
  // that of a fresh factor.
  StageTimers timers;
  Plate plate = make_plate();
  auto system = fresh_system(timers, plate, true);
  system->set_trusted_backward_error(0.0);
  solve(*system, plate);
  for (const std::int32_t e : {5, 6, 60}) plate.model.damage[e] = 0.9;
  const std::vector<double> x = solve(*system, plate);
  EXPECT_EQ(system->stats().folded_damage_passes, 1);
  EXPECT_EQ(system->stats().untrusted_updated_solves, 1);
  EXPECT_EQ(system->solver_stats().factorizations, 2);
  EXPECT_LT(relative_difference(x, fresh_solution(plate)), 1e-12);
  // The refactorized factor is fresh: the next solve is not checked, so not refused.
  solve(*system, plate);
  EXPECT_EQ(system->stats().untrusted_updated_solves, 1);
}

TEST(LinearSystem, WithoutFactorUpdatesEveryDamageChangeIsAssembledAndFactorizedAfresh) {
  StageTimers timers;
  Plate plate = make_plate();
  auto system = fresh_system(timers, plate, false);
  solve(*system, plate);
  plate.model.damage[10] = 0.5;
  solve(*system, plate);
  EXPECT_EQ(system->stats().folded_damage_passes, 0);
  EXPECT_EQ(system->solver_stats().factorizations, 2);
}

TEST(LinearSystem, ChangeOfManyElementsIsAssembledAfreshNotFolded) {
  // Past the cost model's break-even (0.45 sqrt(n) + 4000 / sqrt(max(n, 5000)) update columns a
  // factorization, 3 columns an element) a factorization is cheaper than the updates.
  StageTimers timers;
  Plate plate = make_plate();
  auto system = fresh_system(timers, plate, true);
  solve(*system, plate);
  std::fill(plate.model.damage.begin(), plate.model.damage.end(), 0.3);
  const std::vector<double> x = solve(*system, plate);
  EXPECT_EQ(system->stats().folded_damage_passes, 0);
  EXPECT_EQ(system->solver_stats().factorizations, 2);
  EXPECT_EQ(x, fresh_solution(plate));  // assembled afresh: bitwise a fresh system
}

}  // namespace
}  // namespace rockdd

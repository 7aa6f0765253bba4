// Factor updates in the fracture loop (docs/benchmarks.md, "Damage passes folded into the
// factor"): a damage pass that changes few element moduli, or an open-close iteration that
// switches few springs, modifies the Cholesky factor by low-rank updates (cholmod_updown),
// and each solve with an updated factor is checked against the assembled matrix.
// It changes round-off only. Each test runs one scene twice, [solver] factor_updates = true
// (the default) and false (refactorize every time), and asks for the same physical run: the
// same numbers of steps, open-close iterations, damage passes, damaged elements and blocks,
// and every history value within 1e-6 of its column's largest magnitude.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/scene_run.hpp"

namespace rockdd {
namespace {

/// Runs data/`name` with factor updates on and off; checks that the two runs are the same
/// run; returns the one with updates.
test::SceneRun expect_same_run(const std::string& name, std::vector<std::string> overrides) {
  std::vector<std::string> off = overrides;
  off.push_back("solver.factor_updates=false");
  const auto with = test::run_data_scene(name, overrides, 1);
  const auto without = test::run_data_scene(name, off, 1);
  EXPECT_TRUE(with.result.ok) << with.result.reason;
  EXPECT_TRUE(without.result.ok) << without.result.reason;
  const auto& a = with.result.summary;
  const auto& b = without.result.summary;
  for (const char* key : {"steps", "redone_steps", "open_close_iterations", "damage_iterations",
                          "damaged_elements", "detached_elements", "blocks"})
    if (a.contains(key)) {
      EXPECT_EQ(a.at(key), b.at(key)) << key;
    }
  EXPECT_EQ(b.at("solver").at("updates").get<long>(), 0);
  EXPECT_EQ(with.history.size(), without.history.size());
  for (const auto& [column, values] : with.history) {
    const auto& other = without.history.at(column);
    EXPECT_EQ(values.size(), other.size()) << column;
    // The balance's remainder is round-off of the work's size: measured against the work.
    const auto& scale = column == "energy.unaccounted" ? without.history.at("energy.external_work")
                                                       : other;
    double largest = 0.0, difference = 0.0;
    for (std::size_t i = 0; i < std::min(values.size(), other.size()); ++i) {
      largest = std::max(largest, std::abs(scale[i]));
      difference = std::max(difference, std::abs(values[i] - other[i]));
    }
    EXPECT_LE(difference, 1e-6 * largest) << column;
  }
  return with;
}

TEST(FactorUpdates, SlidingBlockSwitchesItsContactsAsWithRefactorization) {
  // Paper benchmark 2: contacts open, slide and lock; springs switched in an open-close
  // iteration are folded in when few change.
  const auto run = expect_same_run("sliding_block.toml", {"time.end=0.3"});
  EXPECT_GT(run.result.summary.at("solver").at("updates").get<long>(), 0);
}

TEST(FactorUpdates, BrazilianDiskCracksAsWithRefactorization) {
  // The homogeneous disk under displacement control, through its split (90 % load drop).
  const auto run = expect_same_run("brazilian_disk_displacement.toml", {"output.every=0"});
  EXPECT_GT(run.result.summary.at("folded_damage_passes").get<long>(), 0);
}

TEST(FactorUpdates, UniaxialCompressionDamagesAsWithRefactorization) {
  // The paper's heterogeneous specimen on 900 elements, to 20 % softening.
  const auto run =
      expect_same_run("uniaxial_compression.toml",
                      {"mesh.divisions=[15, 30]", "time.stop_at_softening=0.2", "output.every=0"});
  const auto& summary = run.result.summary;
  EXPECT_GT(summary.at("folded_damage_passes").get<long>(), 0);
  EXPECT_LT(summary.at("solver").at("factorizations").get<long>(),
            summary.at("steps").get<long>() + summary.at("damage_iterations").get<long>());
  // Every pass of a committed step evaluates the laws once (the onset searches come on top),
  // and the damage stage's timer is its own: not the strain pass, not the detachment.
  EXPECT_GE(summary.at("damage_stage_passes").get<long>(),
            summary.at("steps").get<long>() + summary.at("damage_iterations").get<long>());
  EXPECT_GT(summary.at("timers").at("damage").get<double>(), 0.0);
  EXPECT_GT(summary.at("timers").at("detachment").get<double>(), 0.0);
}

}  // namespace
}  // namespace rockdd

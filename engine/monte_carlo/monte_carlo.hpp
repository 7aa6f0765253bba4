#pragma once
// Monte Carlo over heterogeneity seeds (rockdd mc): realization r of a scene draws every
// heterogeneous material with seed first_seed + r, runs to its end like `rockdd run`, and
// leaves its files in <out>/<scene name>/seed_<seed>/. The realizations' summaries are then
// gathered into mc.csv (one row each) and mc.json (mean, spread and range of each number).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// The seeds of a Monte Carlo sweep and where its files go.
struct MonteCarloPlan {
  std::uint64_t first_seed = 0;
  long realizations = 0;
  std::filesystem::path dir;  // <out>/<scene name>
  /// The seed of realization r.
  std::uint64_t seed(long r) const { return first_seed + static_cast<std::uint64_t>(r); }
  /// The run folder of the realization with `seed`.
  std::filesystem::path realization_dir(std::uint64_t seed) const;
};

/// The plan for `realizations` runs of `scene` from `first_seed` (default: the seed of the
/// scene's first heterogeneous material) into `out_root`/<scene name>. Throws InputError when
/// no material of the scene is heterogeneous (nothing for the seed to change).
MonteCarloPlan plan_monte_carlo(const Scene& scene, long realizations,
                                std::optional<std::uint64_t> first_seed,
                                const std::filesystem::path& out_root);

/// The scene of one realization: every heterogeneous material drawn with `seed`.
Scene realization_scene(const Scene& scene, std::uint64_t seed);

/// Reads each realization's summary.json (a missing one counts as a failed run) and writes
/// mc.csv and mc.json into plan.dir. Returns mc.json's content.
nlohmann::json write_monte_carlo_report(const Scene& scene, const MonteCarloPlan& plan);

}  // namespace rockdd

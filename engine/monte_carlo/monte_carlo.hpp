#pragma once
// Monte Carlo over heterogeneity seeds (rockdd mc): realization r of a scene draws every
// heterogeneous material with seed first_seed + r, runs to its end like `rockdd run`, and
// leaves its files in <out>/<scene name>/seed_<seed>/. Each finished realization becomes a
// row of mc.csv (ensemble_table.hpp), and mc.json (the statistics of every column) is
// rewritten from mc.csv after each row.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/monte_carlo/ensemble_manifest.hpp"
#include "engine/monte_carlo/ensemble_table.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Part i (1-based) of n of an ensemble: the realizations r with r % n == i - 1.
struct Shard {
  long index = 1, count = 1;
  /// "i/n", or "" for the whole ensemble.
  std::string text() const;
};

/// The seeds of a Monte Carlo sweep and where its files go.
struct MonteCarloPlan {
  std::uint64_t first_seed = 0;
  long realizations = 0;
  Shard shard;
  std::filesystem::path dir;  // <out>/<scene name>
  /// The seed of realization r.
  std::uint64_t seed(long r) const { return first_seed + static_cast<std::uint64_t>(r); }
  /// The seeds this run (its shard) covers, in order.
  std::vector<std::uint64_t> seeds() const;
  /// The run folder of the realization with `seed`.
  std::filesystem::path realization_dir(std::uint64_t seed) const;
};

/// The plan for `realizations` runs of `scene` from `first_seed` (default: the seed of the
/// scene's first heterogeneous material) into `out_root`/<scene name>. Throws InputError when
/// no material of the scene is heterogeneous (nothing for the seed to change).
MonteCarloPlan plan_monte_carlo(const Scene& scene, long realizations,
                                std::optional<std::uint64_t> first_seed,
                                const std::filesystem::path& out_root, Shard shard = {});

/// The scene of one realization: every heterogeneous material drawn with `seed`.
Scene realization_scene(const Scene& scene, std::uint64_t seed);

/// mc.csv's value columns for `scene`, known before any realization runs (the header is
/// written first): counts, wall time, the first damage time (scenes with damage), the peak
/// of every probe column, the softening peak (scenes that stop at softening); by name.
std::vector<std::string> ensemble_columns(const Scene& scene);

/// The row of a realization that left `summary` (its summary.json): ok or failed.
EnsembleRow realization_row(const std::vector<std::string>& columns, std::uint64_t seed,
                            const nlohmann::json& summary);

/// The row of a realization that ended without a summary (an exception, a killed worker).
EnsembleRow crashed_row(const std::vector<std::string>& columns, std::uint64_t seed,
                        const std::string& reason);

/// mc.json's content for the latest row of every seed in `table`: counts (ok, failed with
/// crashed among them), the identity hash, and ensemble_statistics.
nlohmann::json ensemble_report(const EnsembleIdentity& identity, const EnsembleTable& table);

/// Rewrites `dir`/mc.json (temp + rename) from every row of `dir`/mc.csv; returns it.
nlohmann::json write_ensemble_report(const std::filesystem::path& dir,
                                     const EnsembleIdentity& identity);

}  // namespace rockdd

#include "engine/engine.hpp"
#include "engine/monte_carlo/monte_carlo.hpp"
#include "engine/report/run_result.hpp"
#include "library/api_errors.hpp"
#include "library/scene_impl.hpp"

namespace rockdd::api {
namespace {

/// The realization with `seed`, run to its end in this process; its mc.csv row.
rockdd::EnsembleRow run_realization(const rockdd::Scene& scene, std::uint64_t seed,
                                    const std::vector<std::string>& columns,
                                    const RunSettings& settings) {
  const rockdd::Scene realization = realization_scene(scene, seed);
  rockdd::Simulation simulation(realization, build_scene_model(realization));
  RunOptions options;
  options.write_outputs = !settings.out_dir.empty();
  if (options.write_outputs)
    options.out_dir = std::filesystem::path(settings.out_dir) / ("seed_" + std::to_string(seed));
  options.write_frames = settings.write_frames;
  options.threads = settings.threads;
  return realization_row(columns, seed, simulation.run(options).summary);
}

}  // namespace

EnsembleTable run_ensemble(const Scene& scene, long realizations,
                           std::optional<std::uint64_t> first_seed, const RunSettings& settings) {
  return translate_errors([&] {
    const rockdd::Scene& s = SceneAccess::scene(scene);
    // The plan checks the scene (a heterogeneous material) and numbers the seeds as `rockdd mc`.
    const MonteCarloPlan plan = plan_monte_carlo(s, realizations, first_seed, {});
    EnsembleTable table;
    table.columns = ensemble_columns(s);
    for (const std::uint64_t seed : plan.seeds()) {
      rockdd::EnsembleRow row = run_realization(s, seed, table.columns, settings);
      table.rows.push_back({row.seed, row.status, std::move(row.cells), row.reason});
    }
    return table;
  });
}

}  // namespace rockdd::api

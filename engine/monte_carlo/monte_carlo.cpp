#include "engine/monte_carlo/monte_carlo.hpp"

#include <algorithm>
#include <map>

#include "engine/common/atomic_file.hpp"
#include "engine/common/errors.hpp"
#include "engine/common/number_format.hpp"
#include "engine/monte_carlo/ensemble_statistics.hpp"

namespace rockdd {
namespace {

bool heterogeneous(const MaterialSpec& m) {
  return m.homogeneity && !m.heterogeneous.empty();
}

/// The summary counters that mc.csv tabulates under their own names.
constexpr const char* kCounters[] = {
    "wall_seconds",     "steps", "redone_steps", "open_close_iterations", "damage_iterations",
    "damaged_elements", "blocks"};

/// The numbers of one realization's summary that mc.csv tabulates, by column name: counts,
/// wall time, the first damage, the peak of every probe column and the softening peak.
std::map<std::string, double> tabulated(const nlohmann::json& summary) {
  std::map<std::string, double> row;
  for (const char* key : kCounters)
    if (summary.contains(key) && summary[key].is_number()) row[key] = summary[key].get<double>();
  if (summary.contains("first_damage") && summary["first_damage"].is_object())
    row["first_damage.time"] = summary["first_damage"]["time"].get<double>();
  if (summary.contains("peaks"))
    for (const auto& [column, value] : summary["peaks"].items())
      if (value.is_number()) row["peaks." + column] = value.get<double>();
  if (summary.contains("softening") && summary["softening"].is_object()) {
    row["softening.peak"] = summary["softening"]["peak"].get<double>();
    row["softening.peak_time"] = summary["softening"]["peak_time"].get<double>();
  }
  return row;
}

}  // namespace

std::string Shard::text() const {
  return count == 1 ? std::string() : std::to_string(index) + "/" + std::to_string(count);
}

std::vector<std::uint64_t> MonteCarloPlan::seeds() const {
  std::vector<std::uint64_t> out;
  for (long r = shard.index - 1; r < realizations; r += shard.count) out.push_back(seed(r));
  return out;
}

std::filesystem::path MonteCarloPlan::realization_dir(std::uint64_t s) const {
  return dir / ("seed_" + std::to_string(s));
}

MonteCarloPlan plan_monte_carlo(const Scene& scene, long realizations,
                                std::optional<std::uint64_t> first_seed,
                                const std::filesystem::path& out_root, Shard shard) {
  const auto first = std::find_if(scene.materials.begin(), scene.materials.end(), heterogeneous);
  if (first == scene.materials.end())
    throw InputError(scene.file.string(), "material",
                     "expected a heterogeneous material (homogeneity and heterogeneous) for a "
                     "Monte Carlo run over seeds, got none");
  MonteCarloPlan plan;
  plan.first_seed = first_seed.value_or(first->seed);
  plan.realizations = realizations;
  plan.shard = shard;
  plan.dir = (out_root.empty() ? scene.output.dir : out_root) / scene.name;
  return plan;
}

Scene realization_scene(const Scene& scene, std::uint64_t seed) {
  Scene out = scene;
  for (MaterialSpec& m : out.materials)
    if (heterogeneous(m)) m.seed = seed;
  return out;
}

std::vector<std::string> ensemble_columns(const Scene& scene) {
  std::vector<std::string> columns(std::begin(kCounters), std::end(kCounters));
  if (std::any_of(scene.materials.begin(), scene.materials.end(),
                  [](const MaterialSpec& m) { return m.has_damage(); }))
    columns.push_back("first_damage.time");
  for (const ProbeSpec& probe : scene.probes)
    if (probe.kind != ProbeSpec::Kind::line)
      for (const std::string& field : probe.fields)
        columns.push_back("peaks." + probe.name + "." + field);
  if (scene.time.stop_at_softening) {
    columns.push_back("softening.peak");
    columns.push_back("softening.peak_time");
  }
  // By name, as the table has always been ordered.
  std::sort(columns.begin(), columns.end());
  return columns;
}

EnsembleRow realization_row(const std::vector<std::string>& columns, std::uint64_t seed,
                            const nlohmann::json& summary) {
  EnsembleRow row;
  row.seed = seed;
  row.status = summary.value("status", "failed") == "ok" ? "ok" : "failed";
  row.reason = summary.value("reason", "");
  const std::map<std::string, double> numbers = tabulated(summary);
  for (const std::string& c : columns) {
    const auto found = numbers.find(c);
    row.cells.push_back(found == numbers.end() ? std::string() : format_number(found->second));
  }
  return row;
}

EnsembleRow crashed_row(const std::vector<std::string>& columns, std::uint64_t seed,
                        const std::string& reason) {
  return {seed, "crashed", std::vector<std::string>(columns.size()), reason};
}

nlohmann::json ensemble_report(const EnsembleIdentity& identity, const EnsembleTable& table) {
  const std::vector<EnsembleRow> rows = latest_rows(table.rows);
  const auto count = [&](const char* status) {
    return std::count_if(rows.begin(), rows.end(),
                         [&](const EnsembleRow& r) { return r.status == status; });
  };
  const long ok = count("ok");
  return {{"scene", identity.scene},
          {"realizations", rows.size()},
          {"first_seed", identity.first_seed},
          {"hash", identity.hash()},
          {"ok", ok},
          {"failed", static_cast<long>(rows.size()) - ok},  // crashed ones included
          {"crashed", count("crashed")},
          {"statistics", ensemble_statistics(table.columns, rows)}};
}

nlohmann::json write_ensemble_report(const std::filesystem::path& dir,
                                     const EnsembleIdentity& identity) {
  const nlohmann::json report = ensemble_report(identity, read_ensemble_table(dir / "mc.csv"));
  write_file_atomically(dir / "mc.json", report.dump(2) + "\n");
  return report;
}

}  // namespace rockdd

#include "engine/monte_carlo/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/number_format.hpp"
#include "engine/output/atomic_file.hpp"

namespace rockdd {
namespace {

bool heterogeneous(const MaterialSpec& m) { return m.homogeneity && !m.heterogeneous.empty(); }

/// The numbers of one realization's summary that mc.csv tabulates, by column name: counts,
/// wall time, the first damage, the peak of every probe column and the softening peak.
std::map<std::string, double> tabulated(const nlohmann::json& summary) {
  std::map<std::string, double> row;
  for (const char* key : {"wall_seconds", "steps", "redone_steps", "open_close_iterations",
                          "damage_iterations", "damaged_elements", "blocks"})
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

/// A CSV cell: quoted when it holds a comma or a quote.
std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::filesystem::path MonteCarloPlan::realization_dir(std::uint64_t s) const {
  return dir / ("seed_" + std::to_string(s));
}

MonteCarloPlan plan_monte_carlo(const Scene& scene, long realizations,
                                std::optional<std::uint64_t> first_seed,
                                const std::filesystem::path& out_root) {
  const auto first = std::find_if(scene.materials.begin(), scene.materials.end(), heterogeneous);
  if (first == scene.materials.end())
    throw InputError(scene.file.string(), "material",
                     "expected a heterogeneous material (homogeneity and heterogeneous) for a "
                     "Monte Carlo run over seeds, got none");
  MonteCarloPlan plan;
  plan.first_seed = first_seed.value_or(first->seed);
  plan.realizations = realizations;
  plan.dir = (out_root.empty() ? scene.output.dir : out_root) / scene.name;
  return plan;
}

Scene realization_scene(const Scene& scene, std::uint64_t seed) {
  Scene out = scene;
  for (MaterialSpec& m : out.materials)
    if (heterogeneous(m)) m.seed = seed;
  return out;
}

nlohmann::json write_monte_carlo_report(const Scene& scene, const MonteCarloPlan& plan) {
  std::vector<nlohmann::json> summaries;
  std::vector<std::string> columns;  // in first-seen order
  std::vector<std::map<std::string, double>> rows;
  for (long r = 0; r < plan.realizations; ++r) {
    const std::filesystem::path file = plan.realization_dir(plan.seed(r)) / "summary.json";
    nlohmann::json summary;
    std::ifstream in(file);
    try {
      if (in) summary = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception&) {
      summary = nullptr;
    }
    if (!summary.is_object())
      summary = {{"status", "failed"}, {"reason", "no readable summary.json (the run crashed)"}};
    rows.push_back(tabulated(summary));
    for (const auto& [column, value] : rows.back())
      if (std::find(columns.begin(), columns.end(), column) == columns.end())
        columns.push_back(column);
    summaries.push_back(std::move(summary));
  }

  std::ostringstream csv;
  csv << "seed,status";
  for (const std::string& c : columns) csv << ',' << csv_cell(c);
  csv << ",reason\n";
  long ok = 0;
  std::map<std::string, std::vector<double>> values;  // over the realizations that ran to the end
  for (long r = 0; r < plan.realizations; ++r) {
    const nlohmann::json& s = summaries[static_cast<std::size_t>(r)];
    const bool run_ok = s.value("status", "failed") == "ok";
    ok += run_ok;
    csv << plan.seed(r) << ',' << (run_ok ? "ok" : "failed");
    for (const std::string& c : columns) {
      const auto found = rows[static_cast<std::size_t>(r)].find(c);
      csv << ',';
      if (found == rows[static_cast<std::size_t>(r)].end()) continue;
      csv << format_number(found->second);
      if (run_ok) values[c].push_back(found->second);
    }
    csv << ',' << csv_cell(s.value("reason", "")) << '\n';
  }
  write_file_atomically(plan.dir / "mc.csv", csv.str());

  nlohmann::json statistics = nlohmann::json::object();
  for (const std::string& c : columns) {
    const std::vector<double>& v = values[c];
    if (v.empty()) continue;
    const double n = static_cast<double>(v.size());
    double mean = 0.0;
    for (const double x : v) mean += x / n;
    double variance = 0.0;
    for (const double x : v) variance += (x - mean) * (x - mean);
    const double stddev = v.size() > 1 ? std::sqrt(variance / (n - 1.0)) : 0.0;
    statistics[c] = {{"mean", mean},
                     {"std", stddev},
                     {"min", *std::min_element(v.begin(), v.end())},
                     {"max", *std::max_element(v.begin(), v.end())},
                     {"count", v.size()}};
  }
  nlohmann::json report = {{"scene", scene.name},
                           {"realizations", plan.realizations},
                           {"first_seed", plan.first_seed},
                           {"ok", ok},
                           {"failed", plan.realizations - ok},
                           {"statistics", statistics}};
  write_file_atomically(plan.dir / "mc.json", report.dump(2) + "\n");
  return report;
}

}  // namespace rockdd

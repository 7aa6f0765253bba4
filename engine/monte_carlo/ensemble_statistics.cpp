#include "engine/monte_carlo/ensemble_statistics.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include "engine/monte_carlo/weibull_fit.hpp"

namespace rockdd {
namespace {

/// A cell's number; nothing for an empty or non-numeric cell.
std::optional<double> number_in(const std::string& cell) {
  double value = 0.0;
  const auto parsed = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || parsed.ec != std::errc() || parsed.ptr != cell.data() + cell.size())
    return std::nullopt;
  return value;
}

nlohmann::json weibull_json(const WeibullFit& fit) {
  return {{"shape", fit.shape},
          {"scale", fit.scale},
          {"shape_ci90", {fit.shape_low, fit.shape_high}},
          {"scale_ci90", {fit.scale_low, fit.scale_high}},
          {"method",
           "maximum likelihood; 90 % Wald intervals on ln(shape) and ln(scale) from the "
           "observed Fisher information"}};
}

}  // namespace

double quantile_of_sorted(std::span<const double> sorted, double q) {
  if (sorted.empty()) return std::nan("");
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const auto below = static_cast<std::size_t>(std::floor(h));
  if (below + 1 >= sorted.size()) return sorted.back();
  return sorted[below] + (h - static_cast<double>(below)) * (sorted[below + 1] - sorted[below]);
}

bool is_strength_column(const std::string& column) {
  if (column == "softening.peak") return true;
  return column.starts_with("peaks.") && (column.ends_with(".fx") || column.ends_with(".fy"));
}

nlohmann::json column_statistics(const std::string& column, std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  double mean = 0.0;
  for (const double x : values) mean += x / n;
  double squares = 0.0;
  for (const double x : values) squares += (x - mean) * (x - mean);
  nlohmann::json stats = {{"mean", mean},
                          {"std", values.size() > 1 ? std::sqrt(squares / (n - 1.0)) : 0.0},
                          {"min", values.front()},
                          {"max", values.back()},
                          {"count", values.size()},
                          {"q05", quantile_of_sorted(values, 0.05)},
                          {"q50", quantile_of_sorted(values, 0.50)},
                          {"q95", quantile_of_sorted(values, 0.95)}};
  if (is_strength_column(column))
    if (const auto fit = fit_weibull(values)) stats["weibull"] = weibull_json(*fit);
  return stats;
}

nlohmann::json ensemble_statistics(const std::vector<std::string>& columns,
                                   const std::vector<EnsembleRow>& rows) {
  nlohmann::json statistics = nlohmann::json::object();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    std::vector<double> values;
    for (const EnsembleRow& row : rows)
      if (row.status == "ok" && c < row.cells.size())
        if (const auto x = number_in(row.cells[c])) values.push_back(*x);
    if (!values.empty()) statistics[columns[c]] = column_statistics(columns[c], std::move(values));
  }
  return statistics;
}

}  // namespace rockdd

#pragma once
// The statistics of an ensemble's table (mc.json's "statistics"): per numeric column over the
// realizations that ran to their end with status ok.
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/monte_carlo/ensemble_table.hpp"

namespace rockdd {

/// The q-quantile (0 <= q <= 1) of sorted values: linear interpolation between the order
/// statistics at (n - 1) q (Hyndman and Fan's type 7, numpy's and R's default).
double quantile_of_sorted(std::span<const double> sorted, double q);

/// True for a peak strength column: the peak of a probe force (peaks.<probe>.fx / .fy) or the
/// softening peak; these get a Weibull fit.
bool is_strength_column(const std::string& column);

/// One column's statistics: count, mean, std (sample), min, max, q05, q50, q95, and for a
/// strength column a Weibull fit ("weibull": shape, scale, 90 % intervals).
nlohmann::json column_statistics(const std::string& column, std::vector<double> values);

/// mc.json's "statistics": every column with at least one number in an ok row.
nlohmann::json ensemble_statistics(const std::vector<std::string>& columns,
                                   const std::vector<EnsembleRow>& rows);

}  // namespace rockdd

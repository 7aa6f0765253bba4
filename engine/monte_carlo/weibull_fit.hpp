#pragma once
// Two-parameter Weibull fit of an ensemble's peak strengths: P(X <= x) = 1 - exp(-(x/scale)^m).
#include <optional>
#include <span>

namespace rockdd {

/// Maximum-likelihood Weibull parameters with 90 % confidence intervals.
struct WeibullFit {
  double shape = 0.0, scale = 0.0;  // m (Weibull modulus) and the scale (units of the data)
  double shape_low = 0.0, shape_high = 0.0;  // 90 % confidence interval of m
  double scale_low = 0.0, scale_high = 0.0;  // 90 % confidence interval of the scale
};

/// The maximum-likelihood fit of `x` (every value > 0); nothing when fewer than two values,
/// a value <= 0 or not finite, or all values equal (no finite m).
std::optional<WeibullFit> fit_weibull(std::span<const double> x);

}  // namespace rockdd

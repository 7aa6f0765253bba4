#include "engine/monte_carlo/weibull_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rockdd {
namespace {

/// Two-sided 90 %: the standard normal's 95 % quantile.
constexpr double kZ90 = 1.6448536269514722;

/// The ML equation for m, g(m) = sum y^m ln y / sum y^m - 1/m - mean(ln y), on y = x / max(x):
/// increasing in m, and y <= 1 keeps y^m from overflowing at any m.
double ml_equation(std::span<const double> log_y, double mean_log_y, double m) {
  double s0 = 0.0, s1 = 0.0;
  for (const double l : log_y) {
    const double w = std::exp(m * l);
    s0 += w;
    s1 += w * l;
  }
  return s1 / s0 - 1.0 / m - mean_log_y;
}

/// The root of ml_equation: bracketed by doubling, then bisection (robust, and 200 halvings
/// reach the last bit of any bracket).
double solve_shape(std::span<const double> log_y, double mean_log_y) {
  double low = 1e-3, high = 1.0;
  while (ml_equation(log_y, mean_log_y, low) > 0.0 && low > 1e-12) low /= 2.0;
  while (ml_equation(log_y, mean_log_y, high) < 0.0 && high < 1e9) high *= 2.0;
  for (int i = 0; i < 200 && high - low > 1e-14 * high; ++i) {
    const double mid = 0.5 * (low + high);
    (ml_equation(log_y, mean_log_y, mid) < 0.0 ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace

std::optional<WeibullFit> fit_weibull(std::span<const double> x) {
  if (x.size() < 2) return std::nullopt;
  for (const double v : x)
    if (!(v > 0.0) || !std::isfinite(v)) return std::nullopt;
  const auto [lowest, highest] = std::minmax_element(x.begin(), x.end());
  if (*lowest == *highest) return std::nullopt;
  const double n = static_cast<double>(x.size());
  const double x_max = *highest;
  std::vector<double> log_y(x.size());
  double mean_log_y = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    log_y[i] = std::log(x[i] / x_max);
    mean_log_y += log_y[i] / n;
  }
  WeibullFit fit;
  const double m = solve_shape(log_y, mean_log_y);
  double sum_w = 0.0;
  for (const double l : log_y) sum_w += std::exp(m * l);
  fit.shape = m;
  fit.scale = x_max * std::pow(sum_w / n, 1.0 / m);

  // Confidence intervals from the observed Fisher information J (minus the Hessian of the
  // log-likelihood at the optimum, where sum z = n with z = (x / scale)^m, l = ln(x / scale)):
  //   J_mm = n / m^2 + sum z l^2,  J_ss = n m^2 / scale^2,  J_ms = -(m / scale) sum z l.
  // The Wald intervals are taken on ln m and ln scale, so that they stay positive.
  double sum_zl = 0.0, sum_zll = 0.0;
  for (const double v : x) {
    const double l = std::log(v / fit.scale), z = std::exp(m * l);
    sum_zl += z * l;
    sum_zll += z * l * l;
  }
  const double j_mm = n / (m * m) + sum_zll;
  const double j_ss = n * m * m / (fit.scale * fit.scale);
  const double j_ms = -(m / fit.scale) * sum_zl;
  const double det = j_mm * j_ss - j_ms * j_ms;
  const double se_m = std::sqrt(j_ss / det), se_scale = std::sqrt(j_mm / det);
  fit.shape_low = m * std::exp(-kZ90 * se_m / m);
  fit.shape_high = m * std::exp(kZ90 * se_m / m);
  fit.scale_low = fit.scale * std::exp(-kZ90 * se_scale / fit.scale);
  fit.scale_high = fit.scale * std::exp(kZ90 * se_scale / fit.scale);
  return fit;
}

}  // namespace rockdd

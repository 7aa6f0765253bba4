#include "kernels/contact_energy.hpp"

namespace rockdd::kernels {

MeanNormalForce mean_normal_force(bool closed_at_start, bool closed_at_end, double g0, double g1,
                                  double kn) {
  if (closed_at_start && closed_at_end) return {0.5 * kn * (g0 + g1), 0.5 * kn};
  if (closed_at_start) {
    if (g0 >= 0.0 || g1 <= 0.0) return {};
    const double span = g1 - g0;  // > -g0 > 0
    const double share = -g0 / span;
    return {0.5 * kn * g0 * share, 0.5 * kn * share * share};
  }
  if (!closed_at_end) return {};
  if (g0 <= 0.0 || g1 >= 0.0) return {0.5 * kn * g1, 0.5 * kn};
  const double span = g0 - g1;  // > g0 > 0
  const double share = -g1 / span;
  const double before = g0 / span;
  return {0.5 * kn * g1 * share, 0.5 * kn * (1.0 - before * before)};
}

}  // namespace rockdd::kernels

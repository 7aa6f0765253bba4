#include "kernels/principal.hpp"

#include <cmath>

namespace rockdd::kernels {

void principal_values(double xx, double yy, double xy, double& p1, double& p2) {
  // Mohr's circle: centre (xx + yy) / 2, radius sqrt(((xx - yy) / 2)^2 + xy^2) >= 0.
  const double centre = 0.5 * (xx + yy);
  const double half_diff = 0.5 * (xx - yy);
  const double radius = std::sqrt(half_diff * half_diff + xy * xy);
  p1 = centre + radius;
  p2 = centre - radius;
}

double principal_angle(double xx, double yy, double xy) {
  // tan(2 theta) = 2 xy / (xx - yy); atan2 picks the root of the larger value, in (-pi/2, pi/2].
  return 0.5 * std::atan2(2.0 * xy, xx - yy);
}

void principal_strains(const double eps[3], double& e1, double& e2) {
  principal_values(eps[0], eps[1], 0.5 * eps[2], e1, e2);
}

}  // namespace rockdd::kernels

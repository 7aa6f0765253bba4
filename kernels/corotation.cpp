#include "kernels/corotation.hpp"

#include <cmath>
#include <utility>

#include "kernels/cst.hpp"

namespace rockdd::kernels {

double element_rotation(const double xy0[6], const double xy[6]) {
  // F = dx/dX = sum_k x_k (grad N_k)^T, constant over the triangle. In 2D the rotation
  // factor of F = R U is the angle atan2(F21 - F12, F11 + F22).
  double b[3], c[3];
  const double two_area = 2.0 * cst_gradients(xy0, b, c);
  double f[2][2] = {{0, 0}, {0, 0}};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 2; ++i) {
      f[i][0] += xy[2 * k + i] * b[k] / two_area;
      f[i][1] += xy[2 * k + i] * c[k] / two_area;
    }
  return std::atan2(f[1][0] - f[0][1], f[0][0] + f[1][1]);
}

namespace {

/// (p, q) = sign(A) (F11 + F22, F21 - F12) 2|A|: the rotation factor of F, not normalised.
/// 2A F = sum_k x_k (b_k, c_k): the factor 2A scales both components alike, so it drops out
/// of the normalisation but for its sign (an inverted reference would turn R by pi).
std::pair<double, double> unnormalised_rotation(const double xy0[6], const double xy[6]) {
  double b[3], c[3];
  const double two_area = 2.0 * cst_gradients(xy0, b, c);
  double f11 = 0.0, f12 = 0.0, f21 = 0.0, f22 = 0.0;
  for (int k = 0; k < 3; ++k) {
    f11 += xy[2 * k] * b[k];
    f12 += xy[2 * k] * c[k];
    f21 += xy[2 * k + 1] * b[k];
    f22 += xy[2 * k + 1] * c[k];
  }
  const double sign = two_area < 0.0 ? -1.0 : 1.0;
  return {sign * (f11 + f22), sign * (f21 - f12)};
}

}  // namespace

Rotation element_rotation_factor(const double xy0[6], const double xy[6]) {
  const auto [p, q] = unnormalised_rotation(xy0, xy);
  const double r = std::sqrt(p * p + q * q);
  if (!(r > 0.0)) return {};  // F = 0 or a pure reflection: atan2(0, 0) = 0 as well
  return {p / r, q / r};
}

bool turned_within(const double xy0[6], const double xy[6], Rotation frame, double bound) {
  const auto [p, q] = unnormalised_rotation(xy0, xy);
  // r (cos, sin) of the turn relative to the frame, r = |(p, q)|. A tangent under bound / 2
  // puts the turn under atan(bound / 2) < bound, a margin far above the round-off of p and q.
  const double along = p * frame.cs + q * frame.sn;
  const double across = q * frame.cs - p * frame.sn;
  return along > 0.0 && std::abs(across) < 0.5 * bound * along;
}

void corotated_displacement(const double xy0[6], const double xy[6], Rotation r, double u[6]) {
  const double cs = r.cs, sn = r.sn;
  const double xc = (xy[0] + xy[2] + xy[4]) / 3.0, yc = (xy[1] + xy[3] + xy[5]) / 3.0;
  const double x0c = (xy0[0] + xy0[2] + xy0[4]) / 3.0, y0c = (xy0[1] + xy0[3] + xy0[5]) / 3.0;
  for (int k = 0; k < 3; ++k) {
    const double dx = xy[2 * k] - xc, dy = xy[2 * k + 1] - yc;
    u[2 * k] = cs * dx + sn * dy - (xy0[2 * k] - x0c);
    u[2 * k + 1] = -sn * dx + cs * dy - (xy0[2 * k + 1] - y0c);
  }
}

void rotate_nodal(Rotation r, double v[6]) {
  const double cs = r.cs, sn = r.sn;
  for (int k = 0; k < 3; ++k) {
    const double x = v[2 * k], y = v[2 * k + 1];
    v[2 * k] = cs * x - sn * y;
    v[2 * k + 1] = sn * x + cs * y;
  }
}

void rotate_element_matrix(Rotation r, double k[36]) {
  const double cs = r.cs, sn = r.sn;
  // T k T^T with T block diagonal: rotate the columns (k T^T), then the rows (T (k T^T)).
  for (int i = 0; i < 6; ++i)
    for (int n = 0; n < 3; ++n) {
      double* row = &k[6 * i + 2 * n];
      const double x = row[0], y = row[1];
      row[0] = cs * x - sn * y;
      row[1] = sn * x + cs * y;
    }
  for (int n = 0; n < 3; ++n)
    for (int col = 0; col < 6; ++col) {
      double& x = k[6 * (2 * n) + col];
      double& y = k[6 * (2 * n + 1) + col];
      const double a = x, b = y;
      x = cs * a - sn * b;
      y = sn * a + cs * b;
    }
}

void rotate_tensor(Rotation r, double s[3]) {
  const double cs = r.cs, sn = r.sn;
  const double xx = s[0], yy = s[1], xy = s[2];
  s[0] = cs * cs * xx - 2.0 * cs * sn * xy + sn * sn * yy;
  s[1] = sn * sn * xx + 2.0 * cs * sn * xy + cs * cs * yy;
  s[2] = cs * sn * (xx - yy) + (cs * cs - sn * sn) * xy;
}

}  // namespace rockdd::kernels

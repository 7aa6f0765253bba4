// Principal values and directions of symmetric 2x2 tensors.
#include "kernels/principal.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

namespace {

namespace k = rockdd::kernels;

// Tensor with principal values p1, p2 and the p1 direction at angle theta:
// xx = p1 cos^2 + p2 sin^2, yy = p1 sin^2 + p2 cos^2, xy = (p1 - p2) sin cos.
struct Tensor {
  double xx, yy, xy;
};
Tensor rotated(double p1, double p2, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {p1 * c * c + p2 * s * s, p1 * s * s + p2 * c * c, (p1 - p2) * s * c};
}

// Difference of two axis angles modulo pi (a direction and its opposite are the same axis).
double axis_gap(double a, double b) {
  const double d = std::remainder(a - b, M_PI);
  return std::fabs(d);
}

TEST(PrincipalValues, DiagonalTensorsInEitherOrder) {
  // diag(3, -2) and diag(-2, 3): p1 = 3, p2 = -2, exactly; p1 along x (0) and y (pi/2).
  double p1, p2;
  k::principal_values(3.0, -2.0, 0.0, p1, p2);
  EXPECT_EQ(p1, 3.0);
  EXPECT_EQ(p2, -2.0);
  EXPECT_EQ(k::principal_angle(3.0, -2.0, 0.0), 0.0);
  k::principal_values(-2.0, 3.0, 0.0, p1, p2);
  EXPECT_EQ(p1, 3.0);
  EXPECT_EQ(p2, -2.0);
  EXPECT_NEAR(k::principal_angle(-2.0, 3.0, 0.0), M_PI / 2, 1e-15);
}

TEST(PrincipalValues, PureShear) {
  // {0, 0, tau}: p = +-|tau|, p1 at +45 deg for tau > 0 and -45 deg for tau < 0 (1e-15).
  for (double tau : {2.5e6, -2.5e6}) {
    double p1, p2;
    k::principal_values(0.0, 0.0, tau, p1, p2);
    EXPECT_EQ(p1, std::fabs(tau));
    EXPECT_EQ(p2, -std::fabs(tau));
    EXPECT_NEAR(k::principal_angle(0.0, 0.0, tau), std::copysign(M_PI / 4, tau), 1e-15);
  }
}

TEST(PrincipalValues, EqualBiaxialHasEqualValuesAndAFiniteAngle) {
  // {s, s, 0}: p1 = p2 = s exactly; every direction is principal, the angle only has to be
  // a finite number.
  double p1, p2;
  k::principal_values(-4e6, -4e6, 0.0, p1, p2);
  EXPECT_EQ(p1, -4e6);
  EXPECT_EQ(p2, -4e6);
  EXPECT_TRUE(std::isfinite(k::principal_angle(-4e6, -4e6, 0.0)));
}

TEST(PrincipalValues, RecoversRotatedDiagonalTensors) {
  // Build T = R diag(p1, p2) R^T for p1 > p2 and several theta; the kernel must give back
  // p1, p2 (1e-14 relative to max |p|) and theta modulo pi (1e-12 rad).
  const double pairs[][2] = {{5.0, 1.0}, {1.0, -3.0}, {-1.0, -7.0}, {2e6, -2e6}, {1e-4, 9e-5}};
  for (const auto& p : pairs) {
    for (double theta : {0.1, 0.7, -0.4, 1.3, -1.5, 2.0}) {
      const Tensor t = rotated(p[0], p[1], theta);
      double p1, p2;
      k::principal_values(t.xx, t.yy, t.xy, p1, p2);
      const double scale = std::max(std::fabs(p[0]), std::fabs(p[1]));
      EXPECT_NEAR(p1, p[0], 1e-14 * scale);
      EXPECT_NEAR(p2, p[1], 1e-14 * scale);
      EXPECT_LE(axis_gap(k::principal_angle(t.xx, t.yy, t.xy), theta), 1e-12);
    }
  }
}

TEST(PrincipalValues, OrderingInvariantsAndEigenvectorOnRandomTensors) {
  // p1 >= p2; p1 + p2 = xx + yy and p1 p2 = xx yy - xy^2 to 1e-14 relative to |T|, |T|^2
  // (|T| = max |component|); (T - p1 I) n = 0 for n = (cos a, sin a), 1e-13 relative to |T|;
  // and agreement with Eigen's symmetric eigensolver to 1e-14 relative.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const double xx = 1e7 * unit(rng), yy = 1e7 * unit(rng), xy = 1e7 * unit(rng);
    const double norm = std::max({std::fabs(xx), std::fabs(yy), std::fabs(xy)});
    double p1, p2;
    k::principal_values(xx, yy, xy, p1, p2);
    EXPECT_GE(p1, p2);
    EXPECT_NEAR(p1 + p2, xx + yy, 1e-14 * norm);
    EXPECT_NEAR(p1 * p2, xx * yy - xy * xy, 1e-14 * norm * norm);
    const double a = k::principal_angle(xx, yy, xy);
    const double nx = std::cos(a), ny = std::sin(a);
    EXPECT_NEAR((xx - p1) * nx + xy * ny, 0.0, 1e-13 * norm);
    EXPECT_NEAR(xy * nx + (yy - p1) * ny, 0.0, 1e-13 * norm);
    Eigen::Matrix2d m;
    m << xx, xy, xy, yy;
    const Eigen::Vector2d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m).eigenvalues();
    EXPECT_NEAR(p1, lambda[1], 1e-14 * norm);
    EXPECT_NEAR(p2, lambda[0], 1e-14 * norm);
  }
}

TEST(PrincipalStrains, UseHalfTheEngineeringShear) {
  // {exx, eyy, gxy} has tensor shear exy = gxy / 2: pure engineering shear gxy = 2g gives
  // e = +-g exactly; a general strain matches the tensor [exx gxy/2; gxy/2 eyy] (1e-14 rel).
  const double shear[3] = {0.0, 0.0, 4e-4};
  double e1, e2;
  k::principal_strains(shear, e1, e2);
  EXPECT_EQ(e1, 2e-4);
  EXPECT_EQ(e2, -2e-4);

  const double eps[3] = {3e-4, -1e-4, 5e-4};
  k::principal_strains(eps, e1, e2);
  Eigen::Matrix2d m;
  m << eps[0], eps[2] / 2, eps[2] / 2, eps[1];
  const Eigen::Vector2d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m).eigenvalues();
  EXPECT_NEAR(e1, lambda[1], 1e-14 * 5e-4);
  EXPECT_NEAR(e2, lambda[0], 1e-14 * 5e-4);
}

}  // namespace

// Co-rotational CST kernels (kernels/corotation.hpp) against exact rigid motions and the
// polar decomposition F = R U of a prescribed deformation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "kernels/corotation.hpp"
#include "kernels/cst.hpp"

namespace rockdd::kernels {
namespace {

constexpr double kXy0[6] = {0.1, 0.2, 1.3, 0.0, 0.4, 0.9};

/// x = F X + shift for each node.
void deform(const double f[2][2], const double shift[2], double xy[6]) {
  for (int k = 0; k < 3; ++k) {
    const double x = kXy0[2 * k], y = kXy0[2 * k + 1];
    xy[2 * k] = f[0][0] * x + f[0][1] * y + shift[0];
    xy[2 * k + 1] = f[1][0] * x + f[1][1] * y + shift[1];
  }
}

TEST(Corotation, RigidMotionLeavesNoDisplacementWhateverTheAngle) {
  // x = R(theta) X + shift: the recovered angle is theta (1e-14) and the co-rotated
  // displacement vanishes (1e-14 of the element size), for angles up to and past pi/2.
  for (const double theta : {0.0, 0.3, 1.5, 2.5, -3.0}) {
    const double f[2][2] = {{std::cos(theta), -std::sin(theta)},
                            {std::sin(theta), std::cos(theta)}};
    const double shift[2] = {5.0, -2.0};
    double xy[6], u[6];
    deform(f, shift, xy);
    EXPECT_NEAR(element_rotation(kXy0, xy), theta, 1e-14);
    corotated_displacement(kXy0, xy, Rotation(element_rotation(kXy0, xy)), u);
    for (const double ui : u) EXPECT_NEAR(ui, 0.0, 1e-14);
  }
}

TEST(Corotation, RotationFactorIsTheCosineAndSineOfTheAngle) {
  // element_rotation_factor normalises (F11 + F22, F21 - F12) instead of taking atan2 and
  // then sincos: the same (cos, sin) to 1e-15, for rotations all round the circle after a
  // stretch U = [[1.01, 0.003], [0.003, 0.995]], and for an element listed clockwise
  // (negative area: 2A scales F's components, so only its sign may be kept).
  for (const double theta : {0.0, 0.3, 1.5, 2.5, 3.1, -1.0, -3.0}) {
    const double c = std::cos(theta), s = std::sin(theta);
    const double u[2][2] = {{1.01, 0.003}, {0.003, 0.995}};
    const double f[2][2] = {{c * u[0][0] - s * u[1][0], c * u[0][1] - s * u[1][1]},
                            {s * u[0][0] + c * u[1][0], s * u[0][1] + c * u[1][1]}};
    const double shift[2] = {-1.0, 3.0};
    double xy[6];
    deform(f, shift, xy);
    const Rotation r = element_rotation_factor(kXy0, xy);
    EXPECT_NEAR(r.cs, c, 1e-15) << theta;
    EXPECT_NEAR(r.sn, s, 1e-15) << theta;
    const double xy0_clockwise[6] = {kXy0[0], kXy0[1], kXy0[4], kXy0[5], kXy0[2], kXy0[3]};
    const double xy_clockwise[6] = {xy[0], xy[1], xy[4], xy[5], xy[2], xy[3]};
    const Rotation turned = element_rotation_factor(xy0_clockwise, xy_clockwise);
    const Rotation angle(element_rotation(xy0_clockwise, xy_clockwise));
    EXPECT_NEAR(turned.cs, angle.cs, 1e-15) << theta;
    EXPECT_NEAR(turned.sn, angle.sn, 1e-15) << theta;
  }
}

TEST(Corotation, TurnedWithinNeverClearsATurnPastItsBound) {
  // turned_within(xy0, xy, frame, bound) may say "within" only when the exact turn relative to
  // the frame, |remainder(theta - phi, 2 pi)| from element_rotation, is below the bound; and it
  // clears every turn below bound / 4 (a stretch of up to 20 % and shear around it), so that
  // only elements near the bound take the exact angle. 20,000 random frames, turns, stretches.
  std::uint64_t state = 12345;
  const auto uniform = [&state](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  const double bound = 1e-3;
  int cleared = 0, exact = 0;
  for (int i = 0; i < 20000; ++i) {
    const double phi = uniform(-4.0, 4.0);
    const double change = i % 2 == 0 ? uniform(-0.25, 0.25) * bound : uniform(-3.0, 3.0) * bound;
    const double theta = phi + (i % 97 == 0 ? 3.0 : 0.0) + change;  // some turned half around
    const double stretch = uniform(0.8, 1.2), shear = uniform(-0.1, 0.1);
    // F = R(theta) U with U symmetric positive definite: its rotation factor is R(theta).
    const double u[2][2] = {{stretch, shear}, {shear, 2.0 - stretch}};
    const double c = std::cos(theta), s = std::sin(theta);
    const double f[2][2] = {{c * u[0][0] - s * u[1][0], c * u[0][1] - s * u[1][1]},
                            {s * u[0][0] + c * u[1][0], s * u[0][1] + c * u[1][1]}};
    const double shift[2] = {uniform(-5.0, 5.0), uniform(-5.0, 5.0)};
    double xy[6];
    deform(f, shift, xy);
    const double turn =
        std::abs(std::remainder(element_rotation(kXy0, xy) - phi, 2.0 * std::numbers::pi));
    const bool within = turned_within(kXy0, xy, Rotation(phi), bound);
    if (within) {
      ++cleared;
      EXPECT_LT(turn, bound) << "frame " << phi << " turn " << turn;
    } else {
      ++exact;
    }
    if (turn < 0.25 * bound) {
      EXPECT_TRUE(within) << "frame " << phi << " turn " << turn;
    }
  }
  EXPECT_GT(cleared, 10000);
  EXPECT_GT(exact, 3000);
}

TEST(Corotation, StretchAfterRotationIsMeasuredInTheElementFrame) {
  // F = R U with U = [[1.01, 0.003], [0.003, 0.995]]: the angle is that of R, and the strain
  // of the co-rotated displacement is exactly {U11 - 1, U22 - 1, 2 U12}.
  const double theta = 1.1, cs = std::cos(theta), sn = std::sin(theta);
  const double uu[2][2] = {{1.01, 0.003}, {0.003, 0.995}};
  const double f[2][2] = {{cs * uu[0][0] - sn * uu[1][0], cs * uu[0][1] - sn * uu[1][1]},
                          {sn * uu[0][0] + cs * uu[1][0], sn * uu[0][1] + cs * uu[1][1]}};
  const double shift[2] = {0.0, 0.0};
  double xy[6], u[6], eps[3];
  deform(f, shift, xy);
  const double angle = element_rotation(kXy0, xy);
  EXPECT_NEAR(angle, theta, 1e-14);
  corotated_displacement(kXy0, xy, Rotation(angle), u);
  cst_strain(kXy0, u, eps);
  EXPECT_NEAR(eps[0], 0.01, 1e-14);
  EXPECT_NEAR(eps[1], -0.005, 1e-14);
  EXPECT_NEAR(eps[2], 0.006, 1e-14);
}

TEST(Corotation, RotatedStiffnessIsTheStiffnessOfTheRotatedElement) {
  // T k(X) T^T = k(R X): the stiffness of a triangle turned by theta, to 1e-12 relative.
  const double theta = 0.8;
  const double f[2][2] = {{std::cos(theta), -std::sin(theta)}, {std::sin(theta), std::cos(theta)}};
  const double shift[2] = {0.0, 0.0};
  double xy[6], d[9], k0[36], k1[36];
  deform(f, shift, xy);
  elasticity_matrix(1e10, 0.25, PlaneKind::stress, d);
  cst_stiffness(kXy0, d, 1.0, k0);
  cst_stiffness(xy, d, 1.0, k1);
  rotate_element_matrix(Rotation(theta), k0);
  for (int i = 0; i < 36; ++i) EXPECT_NEAR(k0[i], k1[i], 1e-12 * 1e10);
}

TEST(Corotation, TensorRotationKeepsInvariantsAndTurnsAxes) {
  // A quarter turn swaps xx and yy and flips xy; any turn keeps the trace and determinant.
  double s[3] = {3.0, -1.0, 0.5};
  rotate_tensor(Rotation(std::acos(-1.0) / 2), s);
  EXPECT_NEAR(s[0], -1.0, 1e-14);
  EXPECT_NEAR(s[1], 3.0, 1e-14);
  EXPECT_NEAR(s[2], -0.5, 1e-14);
  double t[3] = {3.0, -1.0, 0.5};
  rotate_tensor(Rotation(0.37), t);
  EXPECT_NEAR(t[0] + t[1], 2.0, 1e-14);
  EXPECT_NEAR(t[0] * t[1] - t[2] * t[2], -3.25, 1e-13);
}

TEST(Corotation, NodalRotationTurnsEachNode) {
  double v[6] = {1, 0, 0, 1, 2, 2};
  rotate_nodal(Rotation(std::acos(-1.0) / 2), v);
  const double expected[6] = {0, 1, -1, 0, -2, 2};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(v[i], expected[i], 1e-15);
}

}  // namespace
}  // namespace rockdd::kernels

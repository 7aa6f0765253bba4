// Co-rotational CST kernels (kernels/corotation.hpp) against exact rigid motions and the
// polar decomposition F = R U of a prescribed deformation.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "kernels/corotated_cst_batch.hpp"
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

/// One element's co-rotated strain, stress and force as the internal-force pass composes the
/// one-element kernels.
void one_element(const double xy0[6], const double x[6], double young, double poisson,
                 PlaneKind plane, double t, double eps[3], double sig[3], double f[6]) {
  double ue[6], d[9];
  const Rotation turn = element_rotation_factor(xy0, x);
  corotated_displacement(xy0, x, turn, ue);
  elasticity_matrix(young, poisson, plane, d);
  cst_strain(xy0, ue, eps);
  cst_stress(d, eps, sig);
  cst_internal_force(xy0, sig, t, f);
  rotate_nodal(turn, f);
  rotate_tensor(turn, sig);
  eps[2] *= 0.5;
  rotate_tensor(turn, eps);
  eps[2] *= 2.0;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST(CorotatedCstBatch, EqualsTheOneElementKernelsBitForBit) {
  // Not within a tolerance: the pass that uses the batch must leave every history as it was.
  // Random triangles (either orientation, slivers), rotations over the whole circle, strains
  // from 1e-9 to 0.3, moduli down to the damage floor, both plane kinds, partial batches, and
  // elements with no rotation factor (all corners at one point: the identity is kept).
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0;
  for (int round = 0; round < 400; ++round) {
    const PlaneKind plane = round % 2 ? PlaneKind::strain : PlaneKind::stress;
    const int count = 1 + round % kCstBatch;
    CstBatch batch;
    for (int i = 0; i < count; ++i) {
      double xy0[6];
      for (double& v : xy0) v = unit(rng);
      if (i == 3) xy0[4] = 0.5 * (xy0[0] + xy0[2]) + 1e-9, xy0[5] = 0.5 * (xy0[1] + xy0[3]);
      const double theta = std::numbers::pi * unit(rng);
      const double strain = std::pow(10.0, -9.0 + 8.5 * (0.5 + 0.5 * unit(rng)));
      for (int k = 0; k < 3; ++k) {
        const double X = xy0[2 * k] * (1.0 + strain * unit(rng));
        const double Y = xy0[2 * k + 1] * (1.0 + strain * unit(rng));
        batch.xy0[2 * k][i] = xy0[2 * k];
        batch.xy0[2 * k + 1][i] = xy0[2 * k + 1];
        batch.x[2 * k][i] = std::cos(theta) * X - std::sin(theta) * Y + 3.0;
        batch.x[2 * k + 1][i] = std::sin(theta) * X + std::cos(theta) * Y - 1.0;
        if (i == 5) batch.x[2 * k][i] = batch.x[2 * k + 1][i] = 0.25;
      }
      batch.young[i] = damaged_modulus(50e9 * (1.0 + 0.5 * unit(rng)), i == 7 ? 1.0 : 0.0);
      batch.poisson[i] = 0.25 + 0.249 * unit(rng);
    }
    const CstBatch in = batch;
    corotated_cst_forces(batch, count, plane, 0.75);
    for (int i = 0; i < count; ++i) {
      double xy0[6], x[6], eps[3], sig[3], f[6];
      for (int k = 0; k < 6; ++k) {
        xy0[k] = in.xy0[k][i];
        x[k] = in.x[k][i];
      }
      one_element(xy0, x, in.young[i], in.poisson[i], plane, 0.75, eps, sig, f);
      for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(same_bits(batch.strain[k][i], eps[k])) << "round " << round << " lane " << i;
        EXPECT_TRUE(same_bits(batch.stress[k][i], sig[k])) << "round " << round << " lane " << i;
      }
      for (int k = 0; k < 6; ++k)
        EXPECT_TRUE(same_bits(batch.force[k][i], f[k])) << "round " << round << " lane " << i;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 400 / kCstBatch * (kCstBatch * (kCstBatch + 1) / 2));
}

TEST(CorotatedCstBatch, AnElementWithoutRotationFactorKeepsTheIdentity) {
  // All corners at one point: F = 0, whose polar decomposition has no rotation;
  // element_rotation_factor keeps the identity, and so must the lane (its force is then the
  // force of the reference frame's displacement, finite).
  CstBatch batch;
  const double xy0[6] = {0.0, 0.0, 1.0, 0.0, 0.0, 1.0};
  for (int k = 0; k < 6; ++k) {
    batch.xy0[k][0] = xy0[k];
    batch.x[k][0] = 2.0;
  }
  batch.young[0] = 1e9;
  batch.poisson[0] = 0.2;
  corotated_cst_forces(batch, 1, PlaneKind::stress, 1.0);
  double eps[3], sig[3], f[6];
  double x[6];
  for (double& v : x) v = 2.0;
  one_element(xy0, x, 1e9, 0.2, PlaneKind::stress, 1.0, eps, sig, f);
  for (int k = 0; k < 6; ++k) {
    EXPECT_TRUE(std::isfinite(batch.force[k][0]));
    EXPECT_TRUE(same_bits(batch.force[k][0], f[k]));
  }
  // The reference frame's strain of collapsing the unit triangle onto a point: -1 each way.
  EXPECT_DOUBLE_EQ(batch.strain[0][0], -1.0);
  EXPECT_DOUBLE_EQ(batch.strain[1][0], -1.0);
}

TEST(CorotatedCstBatch, TurnedWithinDecidesAsTheOneElementTest) {
  // The frame check takes the batch's answer instead of the one-element test's: the same
  // decision for every lane, at turns on either side of the bound and near it.
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int within_count = 0, compared = 0;
  for (int round = 0; round < 300; ++round) {
    const int count = 1 + round % kCstBatch;
    const double bound = round % 3 == 0 ? 1e-3 : 0.5;
    CstBatch batch;
    double frame_cos[kCstBatch], frame_sin[kCstBatch];
    for (int i = 0; i < count; ++i) {
      const double theta = std::numbers::pi * unit(rng);
      const double frame = theta + bound * 1.5 * unit(rng);
      frame_cos[i] = std::cos(frame);
      frame_sin[i] = std::sin(frame);
      for (int k = 0; k < 3; ++k) {
        const double X = unit(rng), Y = unit(rng);
        batch.xy0[2 * k][i] = X;
        batch.xy0[2 * k + 1][i] = Y;
        batch.x[2 * k][i] = std::cos(theta) * X - std::sin(theta) * Y;
        batch.x[2 * k + 1][i] = std::sin(theta) * X + std::cos(theta) * Y;
      }
    }
    const CstBatch in = batch;
    bool within[kCstBatch];
    turned_within(batch, count, frame_cos, frame_sin, bound, within);
    for (int i = 0; i < count; ++i) {
      double xy0[6], x[6];
      for (int k = 0; k < 6; ++k) {
        xy0[k] = in.xy0[k][i];
        x[k] = in.x[k][i];
      }
      EXPECT_EQ(within[i], turned_within(xy0, x, Rotation(frame_cos[i], frame_sin[i]), bound))
          << "round " << round << " lane " << i;
      within_count += within[i];
      ++compared;
    }
  }
  // Both answers occur.
  EXPECT_GT(within_count, compared / 10);
  EXPECT_LT(within_count, compared - compared / 10);
}

}  // namespace
}  // namespace rockdd::kernels

// The mean normal force of a penalty contact over a step (kernels/contact_energy): the
// discrete gradient of the spring energy Phi(g) = kn g^2 / 2 while closed (0 open), whose work
// over the step, mean * (g1 - g0), is exactly Phi(g0) - Phi(g1) wherever the formula applies.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/contact_energy.hpp"

namespace rockdd::kernels {
namespace {

constexpr double kKn = 2e11;  // N/m: 20 E t for E = 10 GPa, t = 1 m

double energy(bool closed, double gap) {
  return closed ? 0.5 * kKn * gap * gap : 0.0;
}

TEST(MeanNormalForce, WorkOverTheStepIsTheSpringEnergyReleased) {
  // Required: force (g1 - g0) = Phi(g1) - Phi(g0), to 1e-12 of the larger energy (the force
  // as the body pushes the spring: the work the spring does on the body is the energy it
  // releases), for 4000 random steps of each kind: closed at both ends (any gaps), opening
  // (g0 < 0 < g1), closing (g0 > 0 > g1). Gaps of 1e-9 to 1e-5 m. Newmark's own mean,
  // (kn g0 + 0) / 2 for an opening spring, fails it by kn |g0| g1 / 2.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-9.0, -5.0);
  auto gap = [&](double sign) { return sign * std::pow(10.0, exponent(rng)); };
  for (int i = 0; i < 4000; ++i) {
    struct Case {
      bool start, end;
      double g0, g1;
    };
    const Case cases[] = {{true, true, gap(i % 2 ? 1 : -1), gap(i % 3 ? -1 : 1)},
                          {true, false, gap(-1), gap(1)},
                          {false, true, gap(1), gap(-1)}};
    for (const Case& c : cases) {
      const MeanNormalForce m = mean_normal_force(c.start, c.end, c.g0, c.g1, kKn);
      const double work = m.force * (c.g1 - c.g0);
      const double change = energy(c.end, c.g1) - energy(c.start, c.g0);
      const double scale = std::max(energy(true, c.g0), energy(true, c.g1));
      ASSERT_NEAR(work, change, 1e-12 * scale)
          << c.start << c.end << " g0 " << c.g0 << " g1 " << c.g1;
    }
  }
}

TEST(MeanNormalForce, ItsStiffnessIsTheDerivativeInTheEndGap) {
  // Required: stiffness = d force / d g1 (central difference, step 1e-6 of the gap, within
  // 1e-6 relative) and 0 <= stiffness <= kn / 2, the solve's spring being twice it.
  struct Case {
    bool start, end;
    double g0, g1;
  };
  const Case cases[] = {{true, true, -3e-7, -1e-7},
                        {true, false, -3e-7, 2e-7},
                        {true, false, -1e-8, 4e-6},
                        {false, true, 2e-7, -3e-7},
                        {false, true, 5e-6, -1e-8}};
  for (const Case& c : cases) {
    const double h = 1e-6 * std::abs(c.g1);
    const double fd = (mean_normal_force(c.start, c.end, c.g0, c.g1 + h, kKn).force -
                       mean_normal_force(c.start, c.end, c.g0, c.g1 - h, kKn).force) /
                      (2 * h);
    const double k = mean_normal_force(c.start, c.end, c.g0, c.g1, kKn).stiffness;
    EXPECT_NEAR(k, fd, 1e-6 * kKn) << c.start << c.end << " g0 " << c.g0 << " g1 " << c.g1;
    EXPECT_GE(k, 0.0);
    EXPECT_LE(k, 0.5 * kKn);
  }
}

TEST(MeanNormalForce, ContinuousWhereTheOpenCloseIterationSwitchesTheState) {
  // The state at the end switches where g1 crosses zero: the force must not jump there, or
  // the iteration would chatter between two answers. Opening from g0 = -2e-7: at g1 -> 0+ it
  // is the trapezoid's kn g0 / 2 (closed at both ends, g1 = 0); closing from g0 = 2e-7: at
  // g1 -> 0- it is 0, the open spring's. Within 1e-9 of kn g0.
  const double g0 = 2e-7, tiny = 1e-18;
  EXPECT_NEAR(mean_normal_force(true, false, -g0, tiny, kKn).force,
              mean_normal_force(true, true, -g0, 0.0, kKn).force, 1e-9 * kKn * g0);
  EXPECT_NEAR(mean_normal_force(false, true, g0, -tiny, kKn).force, 0.0, 1e-9 * kKn * g0);
  // A mean that vanishes with the time the spring was closed: opening at once, or closing at
  // the very end.
  EXPECT_NEAR(mean_normal_force(true, false, -tiny, g0, kKn).force, 0.0, 1e-9 * kKn * g0);
}

TEST(MeanNormalForce, SpringsThatCannotGiveBackWhatTheyHeldGiveNothing) {
  // Opening from tension (a bonded or in-band spring, g0 >= 0) or taken open while still
  // pressed (g1 <= 0): no force, so the energy it held is lost, never made; open at both ends:
  // none either.
  for (const MeanNormalForce m : {mean_normal_force(true, false, 1e-7, 3e-7, kKn),
                                  mean_normal_force(true, false, -2e-7, -1e-7, kKn),
                                  mean_normal_force(false, false, -2e-7, 1e-7, kKn)}) {
    EXPECT_EQ(m.force, 0.0);
    EXPECT_EQ(m.stiffness, 0.0);
  }
}

}  // namespace
}  // namespace rockdd::kernels

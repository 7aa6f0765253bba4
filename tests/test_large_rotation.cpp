// Large rotations without spurious stress (METHOD.md "Time integration"): co-rotational CST
// and the exact rotation of each free block's step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/time/rotation_correction.hpp"
#include "kernels/cst.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

/// A 1 m x 0.5 m block, no gravity, spinning at `omega` for three turns.
std::string spinning_block(double omega, const std::string& integrator) {
  const double end = 3.0 * 2.0 * std::numbers::pi / omega;
  return test::scene_table("spin", "dynamic", "gravity = [0.0, 0.0]\n") +
         "[time]\ndt = 5e-3\nend = " + std::to_string(end) + "\nintegrator = \"" + integrator +
         "\"\n" + test::rectangle_mesh(1.0, 0.5, {8, 4}) + test::material("*", 2600.0, 10e9, 0.25) +
         "[[initial]]\nbody = \"body\"\nangular_velocity = " + std::to_string(omega) + "\n" +
         test::probe_body("block", "body", {"rotation"}) + test::no_frames("out");
}

class SpinningBlock : public ::testing::TestWithParam<const char*> {};

TEST_P(SpinningBlock, KeepsItsAreaSpeedAndZeroStressForThreeTurns) {
  // omega = 1 rad/s for 3 turns (18.85 s, omega dt = 5e-3). Bounds: area within 0.1 %,
  // angular velocity within 0.5 %, turned angle within 0.5 % of 6 pi; peak stress below
  // 1e-3 of rho (omega L)^2 = E (omega L)^2 / c^2 (2.6 Pa for L = 1 m), the scale of the true
  // centripetal stress; classic DDA's spurious stress would be E (1 - cos theta) ~ E.
  const double omega = 1.0, rho = 2600.0;
  const auto run = test::run_scene_text(spinning_block(omega, GetParam()));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const Model& m = run.model;
  double area = 0.0, area0 = 0.0, peak = 0.0;
  for (std::int32_t e = 0; e < m.num_elements(); ++e) {
    double xy[6];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c) {
        const std::int32_t n = m.conn[3 * e + k];
        xy[2 * k + c] = m.X[2 * n + c] + m.u[2 * n + c];
      }
    area += kernels::cst_signed_area(xy);
    area0 += m.area0[e];
    for (int c = 0; c < 3; ++c) peak = std::max(peak, std::abs(m.stress[3 * e + c]));
  }
  EXPECT_NEAR(area, area0, 1e-3 * area0);
  // Angular velocity about the centre of mass: sum m r x v / sum m r^2.
  double mass = 0, cx = 0, cy = 0;
  for (std::int32_t n = 0; n < m.num_nodes(); ++n) {
    mass += m.node_mass[n];
    cx += m.node_mass[n] * (m.X[2 * n] + m.u[2 * n]);
    cy += m.node_mass[n] * (m.X[2 * n + 1] + m.u[2 * n + 1]);
  }
  cx /= mass;
  cy /= mass;
  double moment = 0, inertia = 0;
  for (std::int32_t n = 0; n < m.num_nodes(); ++n) {
    const double rx = m.X[2 * n] + m.u[2 * n] - cx, ry = m.X[2 * n + 1] + m.u[2 * n + 1] - cy;
    moment += m.node_mass[n] * (rx * m.v[2 * n + 1] - ry * m.v[2 * n]);
    inertia += m.node_mass[n] * (rx * rx + ry * ry);
  }
  EXPECT_NEAR(moment / inertia, omega, 5e-3 * omega);
  EXPECT_NEAR(run.history.at("block.rotation").back(), 6.0 * std::numbers::pi,
              5e-3 * 6.0 * std::numbers::pi);
  EXPECT_LT(peak, 1e-3 * rho * omega * omega * 1.0);
  const auto& strain = run.history.at("energy.strain");
  EXPECT_LT(*std::max_element(strain.begin(), strain.end()), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, SpinningBlock, ::testing::Values("dda", "newmark"));

TEST(RotationCorrection, TurnsAFreeBlockExactlyAndLeavesAHeldOneWhereTheSolveBalancedIt) {
  // A straight-line increment du = theta J r (J r = (-ry, rx) about the centre of mass)
  // becomes the exact turn (R(theta) - I) r of a free block: every corner keeps its distance
  // from the centre to 1e-12 m. A block with one node held (prescribed, or in a closed
  // contact) keeps du as solved, to the bit: turning it would push it by theta^2 r / 2 into
  // whatever holds it.
  const Scene scene = test::scene_from_text(spinning_block(1.0, "dda"), test::TempDir().path());
  const Model model = build_scene_model(scene);
  const std::size_t dofs = model.X.size();
  double mass = 0, cx = 0, cy = 0;
  for (std::int32_t n = 0; n < model.num_nodes(); ++n) {
    mass += model.node_mass[n];
    cx += model.node_mass[n] * model.X[2 * n];
    cy += model.node_mass[n] * model.X[2 * n + 1];
  }
  cx /= mass;
  cy /= mass;
  const double theta = 0.05;
  std::vector<double> linear(dofs);
  for (std::int32_t n = 0; n < model.num_nodes(); ++n) {
    linear[2 * n] = -theta * (model.X[2 * n + 1] - cy);
    linear[2 * n + 1] = theta * (model.X[2 * n] - cx);
  }
  const std::vector<double> u(dofs, 0.0);
  std::vector<double> du = linear, v(dofs, 0.0), a(dofs, 0.0);
  std::vector<std::uint8_t> held(static_cast<std::size_t>(model.num_nodes()), 0);
  correct_block_rotations(model, u, held, du, v, a);
  for (std::int32_t n = 0; n < model.num_nodes(); ++n) {
    const double r0 = std::hypot(model.X[2 * n] - cx, model.X[2 * n + 1] - cy);
    const double r1 =
        std::hypot(model.X[2 * n] + du[2 * n] - cx, model.X[2 * n + 1] + du[2 * n + 1] - cy);
    EXPECT_NEAR(r1, r0, 1e-12);
  }
  du = linear;
  held[0] = 1;
  correct_block_rotations(model, u, held, du, v, a);
  EXPECT_EQ(du, linear);
}

}  // namespace
}  // namespace rockdd

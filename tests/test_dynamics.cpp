// Time integration of a free block (no contact): closed-form rigid-body motion.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace rockdd {
namespace {

std::string free_block(const std::string& integrator, const std::string& extra) {
  return R"(
[scene]
name = "free-block"
analysis = "dynamic"
gravity = [0.0, -10.0]
[time]
dt = 0.01
end = 1.0
integrator = ")" +
         integrator + R"("
[mesh]
shape = "rectangle"
size = [1.0, 0.5]
divisions = [4, 2]
[[material]]
body = "body"
density = 2600.0
young = 10e9
poisson = 0.25
[[probe]]
name = "block"
body = "body"
fields = ["ux", "uy", "vx", "vy", "rotation", "area", "kinetic"]
[output]
every = 0
)" + extra;
}

std::map<std::string, std::vector<double>> run(const std::string& text) {
  const test::SceneRun r = test::run_scene_text(text);
  EXPECT_TRUE(r.result.ok) << r.result.reason;
  return r.history;
}

TEST(FreeBlock, FallsAsHalfGTSquaredWithBothIntegrators) {
  // A free block under gravity: u_y = -g t^2 / 2, v_y = -g t; both schemes integrate a
  // constant acceleration exactly, so 1e-9 relative is round-off.
  for (const char* integrator : {"dda", "newmark"}) {
    const auto h = run(free_block(integrator, ""));
    ASSERT_EQ(h.at("time").size(), 101u) << integrator;
    EXPECT_NEAR(h.at("block.uy").back(), -5.0, 5e-9) << integrator;
    EXPECT_NEAR(h.at("block.vy").back(), -10.0, 1e-8) << integrator;
    EXPECT_NEAR(h.at("block.ux").back(), 0.0, 1e-10) << integrator;
    EXPECT_NEAR(h.at("block.area").back(), 0.5, 1e-12) << integrator;
    // Energy: kinetic = work of gravity = m g h = (2600 * 0.5) * 10 * 5.
    EXPECT_NEAR(h.at("energy.kinetic").back(), 65000.0, 1e-4) << integrator;
    EXPECT_NEAR(h.at("energy.external_work").back(), 65000.0, 1e-4) << integrator;
  }
}

TEST(FreeBlock, InitialVelocityIsKeptWithoutForces) {
  // No gravity, initial velocity (2, 1) m/s: u = v t; momentum is conserved (1e-9: the
  // solve against K + 2M/dt^2 with K ~ 1e10 leaves round-off of about 1e-10 relative).
  std::string text = free_block("dda", "[[initial]]\nbody = \"body\"\nvelocity = [2.0, 1.0]\n");
  text.replace(text.find("gravity = [0.0, -10.0]"), 22, "gravity = [0.0, 0.0]");
  const auto h = run(text);
  EXPECT_NEAR(h.at("block.ux").back(), 2.0, 2e-9);
  EXPECT_NEAR(h.at("block.uy").back(), 1.0, 1e-9);
  EXPECT_NEAR(h.at("block.vx").back(), 2.0, 2e-9);
  EXPECT_NEAR(h.at("block.kinetic").back(), 0.5 * 1300.0 * 5.0, 1e-6);
}

TEST(QuasiStatic, StartsEveryStepAtRest) {
  // Quasi-static (DDA dynamic ratio 0) under gravity with a fixed base: the column settles to
  // the static self-weight solution, where the base reaction equals the weight.
  const std::string text = R"(
[scene]
name = "settle"
analysis = "quasi-static"
gravity = [0.0, -10.0]
[time]
dt = 1.0
steps = 3
[mesh]
shape = "rectangle"
size = [1.0, 2.0]
divisions = [4, 8]
[[material]]
body = "body"
density = 2500.0
young = 1e9
poisson = 0.2
[[boundary]]
on = "bottom"
fix = ["x", "y"]
[[probe]]
name = "base"
on = "bottom"
fields = ["fy"]
[output]
every = 0
)";
  const auto h = run(text);
  // The inertia term 2M/dt^2 is ~1e-6 of K here: the first step already lands on the
  // static answer to that order, and later steps stay there.
  EXPECT_NEAR(h.at("base.fy").back(), 2500.0 * 10.0 * 2.0, 1e-3);
}

}  // namespace
}  // namespace rockdd

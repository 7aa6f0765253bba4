// Blocks in contact, paper benchmark 2: the frictionless sliding block (data/sliding_block.toml).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "test_support.hpp"

namespace rockdd {
namespace {

TEST(SlidingBlock, FrictionlessBlockFollowsTheInclinedPlaneSolution) {
  // Paper eqs. (13)-(14): u_x = 1/2 g cos(th) sin(th) t^2, u_y = -1/2 g sin(th)^2 t^2
  // (downwards), th = 30 deg, g = 10, t = 1.5 s; within 1 % (the tolerance).
  test::TempDir tmp;
  const Scene scene = load_scene(test::data_file("sliding_block.toml"));
  Simulation sim(scene, build_scene_model(scene));
  RunOptions options;
  options.out_root = tmp.path();
  const RunResult result = sim.run(options);
  ASSERT_TRUE(result.ok) << result.reason;
  const auto h = test::read_csv(tmp.path() / "sliding-block" / "history.csv");
  const double th = std::numbers::pi / 6, g = 10.0, t = h.at("time").back();
  EXPECT_NEAR(t, 1.5, 1e-12);
  const double ux = 0.5 * g * std::cos(th) * std::sin(th) * t * t;
  const double uy = -0.5 * g * std::sin(th) * std::sin(th) * t * t;
  EXPECT_NEAR(h.at("block2.ux").back(), ux, 0.01 * std::abs(ux));
  EXPECT_NEAR(h.at("block2.uy").back(), uy, 0.01 * std::abs(uy));
  EXPECT_LT(std::abs(h.at("block2.rotation").back()), 1e-3);  // it slides, it does not tip
  EXPECT_EQ(result.summary["blocks"], 2);
  EXPECT_GT(result.summary["open_close_iterations"].get<long>(), 0);
  EXPECT_TRUE(result.summary["defaults"].contains("contact.normal_stiffness"));
}

TEST(SlidingBlock, SingleBodyWithoutJointBuildsNoContactStage) {
  // No [[joint]]: no detection and no open-close iteration at all (timers.contact stays 0).
  test::TempDir tmp;
  const Scene scene = load_scene(test::data_file("cantilever_model_1.toml"));
  Simulation sim(scene, build_scene_model(scene));
  RunOptions options;
  options.out_root = tmp.path();
  const RunResult result = sim.run(options);
  EXPECT_EQ(result.summary["open_close_iterations"], 0);
  EXPECT_EQ(result.summary["timers"]["contact"], 0.0);
  EXPECT_FALSE(result.summary["defaults"].contains("contact.normal_stiffness"));
}

TEST(Joints, FrictionalJointsAreRejectedUntilValidated) {
  try {
    load_scene(test::data_file("sliding_block.toml"), {"joint.0.friction_angle=15"});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "joint[0].friction_angle");
    EXPECT_NE(std::string(e.what()).find("not supported yet"), std::string::npos);
  }
}

}  // namespace
}  // namespace rockdd

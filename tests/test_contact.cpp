// Blocks in contact, paper benchmark 2: the frictionless sliding block (data/sliding_block.toml).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "support/block_on_base.hpp"
#include "support/rectangle_geo.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"

namespace rockdd {
namespace {

TEST(SlidingBlock, FrictionlessBlockFollowsTheInclinedPlaneSolution) {
  // Paper eqs. (13)-(14): u_x = 1/2 g cos(th) sin(th) t^2, u_y = -1/2 g sin(th)^2 t^2
  // (downwards), th = 30 deg, g = 10, t = 1.5 s; within 1 % (the tolerance).
  const auto run = test::run_data_scene("sliding_block.toml");
  const RunResult& result = run.result;
  ASSERT_TRUE(result.ok) << result.reason;
  const auto& h = run.history;
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

TEST(SlidingBlock, NewmarkAtTenMillisecondStepsKeepsItsEnergy) {
  // The same slide with Newmark's average acceleration at dt = 10 ms, where the contact springs
  // (kn = 20 E t, period about 1e-4 s) are far from resolved. Newmark's trapezoid on the contact
  // forces made energy wherever a spring opened within a step: 38,743 steps (1,926 redone by
  // the energy check), 98 % of the work created and the block tumbling (rotation -3.8 rad).
  // With the step's mean normal force (kernels/contact_energy) the springs give back what they
  // held (measured: 158 steps, none redone by the energy check, |unaccounted| 2.5e-6 of the
  // 21 kJ of work, block II on the closed form to 1e-5). Required: no step redone by the
  // energy check, |unaccounted| and energy created each within 1e-4 of the work, u_x and u_y
  // within 1e-3 of the closed form (as FrictionlessBlockFollowsTheInclinedPlaneSolution), no
  // tipping, under 300 steps.
  const auto run =
      test::run_data_scene("sliding_block.toml", {"time.integrator=newmark", "time.dt=1e-2"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& h = run.history;
  const auto& summary = run.result.summary;
  const double work = summary["energy"]["external_work"].get<double>();
  EXPECT_GT(work, 2e4);
  EXPECT_EQ(summary["redone_by"]["energy"].get<long>(), 0);
  EXPECT_LT(std::abs(summary["energy"]["unaccounted"].get<double>()), 1e-4 * work);
  EXPECT_LT(summary["energy_check"]["created"].get<double>(), 1e-4 * work);
  const double th = std::numbers::pi / 6, g = 10.0, t = h.at("time").back();
  EXPECT_NEAR(t, 1.5, 1e-12);
  const double ux = 0.5 * g * std::cos(th) * std::sin(th) * t * t;
  const double uy = -0.5 * g * std::sin(th) * std::sin(th) * t * t;
  EXPECT_NEAR(h.at("block2.ux").back(), ux, 1e-3 * std::abs(ux));
  EXPECT_NEAR(h.at("block2.uy").back(), uy, 1e-3 * std::abs(uy));
  EXPECT_LT(std::abs(h.at("block2.rotation").back()), 1e-3);
  EXPECT_LT(summary["steps"].get<long>(), 300);
}

TEST(SlidingBlock, SingleBodyWithoutJointBuildsNoContactStage) {
  // No [[joint]]: no detection and no open-close iteration at all (timers.contact stays 0).
  const RunResult result = test::run_data_scene("cantilever_model_1.toml").result;
  EXPECT_EQ(result.summary["open_close_iterations"], 0);
  EXPECT_EQ(result.summary["timers"]["contact"], 0.0);
  EXPECT_FALSE(result.summary["defaults"].contains("contact.normal_stiffness"));
}

/// Runs data/sliding_block.toml with `overrides`; history.csv by column.
std::map<std::string, std::vector<double>> run_sliding_block(
    const std::vector<std::string>& overrides) {
  const auto run = test::run_data_scene("sliding_block.toml", overrides);
  EXPECT_TRUE(run.result.ok) << run.result.reason;
  return run.history;
}

TEST(SlidingBlock, WithFrictionFollowsTheInclinedPlaneSolution) {
  // phi = 15 deg < theta = 30 deg: the block slides with a = g (sin th - cos th tan phi), so
  // along the slope s = 1/2 a t^2, u_x = s cos th, u_y = -s sin th; at t = 1.5 s, within 2 %.
  const auto h = run_sliding_block({"joint.0.friction_angle=15"});
  const double th = std::numbers::pi / 6, phi = std::numbers::pi / 12, g = 10.0;
  const double t = h.at("time").back();
  const double s = 0.5 * g * (std::sin(th) - std::cos(th) * std::tan(phi)) * t * t;
  EXPECT_NEAR(t, 1.5, 1e-12);
  EXPECT_NEAR(h.at("block2.ux").back(), s * std::cos(th), 0.02 * s * std::cos(th));
  EXPECT_NEAR(h.at("block2.uy").back(), -s * std::sin(th), 0.02 * s * std::sin(th));
}

TEST(SlidingBlock, FrictionSteeperThanTheSlopeHoldsTheBlock) {
  // phi = 35 deg > theta = 30 deg: no sliding. Released with unloaded contacts, the block
  // settles within ~0.1 s (elastic compression of both blocks and the release transient:
  // measured 1.1e-4 m, bounded here by 5e-4 m); after that it must not move: less than
  // 1e-6 m between t = 0.2 s and t = 1 s.
  const auto h = run_sliding_block({"joint.0.friction_angle=35", "time.end=1.0"});
  const auto& t = h.at("time");
  const std::size_t settled =
      static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), 0.2) - t.begin());
  ASSERT_LT(settled, t.size());
  const double dx = h.at("block2.ux").back() - h.at("block2.ux")[settled];
  const double dy = h.at("block2.uy").back() - h.at("block2.uy")[settled];
  EXPECT_LT(std::hypot(dx, dy), 1e-6);
  EXPECT_LT(std::hypot(h.at("block2.ux").back(), h.at("block2.uy").back()), 5e-4);
}

/// Block II of data/verification/frictional_incline.toml (theta = 30 deg, phi = 15 deg,
/// g = 10, released from rest), along the slope (down positive): displacement and velocity.
struct InclineRun {
  test::SceneRun run;
  std::vector<double> s, v;
};

InclineRun run_frictional_incline(const std::vector<std::string>& overrides) {
  InclineRun out{test::run_data_scene("verification/frictional_incline.toml", overrides), {}, {}};
  const double th = std::numbers::pi / 6;
  const auto& h = out.run.history;
  for (std::size_t i = 0; i < h.at("time").size(); ++i) {
    out.s.push_back(h.at("block2.ux")[i] * std::cos(th) - h.at("block2.uy")[i] * std::sin(th));
    out.v.push_back(h.at("block2.vx")[i] * std::cos(th) - h.at("block2.vy")[i] * std::sin(th));
  }
  return out;
}

/// s = 1/2 g (sin th - tan phi cos th) t^2, th = 30 deg, phi = 15 deg, g = 10.
double frictional_incline_slide(double t) {
  const double th = std::numbers::pi / 6, phi = std::numbers::pi / 12;
  return 0.5 * 10.0 * (std::sin(th) - std::tan(phi) * std::cos(th)) * t * t;
}

TEST(FrictionalIncline, SlidesAsTheClosedFormAtTenMillisecondSteps) {
  // tan phi < tan theta: the block slides with a = g (sin th - tan phi cos th) = 2.68 m/s^2
  // and never stops. At the scene's dt = 1e-2 s to t = 1 s: s within 1 % of
  // 1/2 a t^2 = 1.3397 m (measured +0.48 %, 100 steps, none redone; it was -67 %), and the
  // velocity along the slope never reverses (it did: at t = 0.30 s one step locked the
  // sliding contacts and the DDA update bounced the block back at -0.89 m/s).
  const InclineRun r = run_frictional_incline({});
  ASSERT_TRUE(r.run.result.ok) << r.run.result.reason;
  const double t = r.run.history.at("time").back();
  EXPECT_NEAR(t, 1.0, 1e-12);
  EXPECT_NEAR(r.s.back(), frictional_incline_slide(t), 0.01 * frictional_incline_slide(t));
  for (std::size_t i = 1; i < r.v.size(); ++i)
    ASSERT_GT(r.v[i], 0.0) << "the block moved up the slope at t = " << r.run.history.at("time")[i];
}

TEST(FrictionalIncline, EnergyBalanceClosesWithSoftAndStiffShearSprings) {
  // Gravity's work W goes into kinetic energy, spring energy and friction:
  // W - kinetic - strain - dissipated (summary.json energy.unaccounted) stays below 1 % of W
  // over the whole run (every history row, against the final W), and no re-solve creates
  // energy (energy.created_by_resolves = 0), with the default ks = 0.4 kn = 8e10 N/m, a
  // softer ks = 1e9 and a stiffer ks = 1e12 (measured at the end: 0.40 %, 0.43 %, 0.39 %,
  // all energy lost, none created; before the fix 34 %, 37 % (824 J lost of 2207 J), and
  // with 1e12 the block left the slope). The block still follows the closed form within
  // 1 % with either spring (measured +0.13 % and +0.48 %).
  for (const std::string ks : {"", "1e9", "1e12"}) {
    const InclineRun r = run_frictional_incline(
        ks.empty() ? std::vector<std::string>{}
                   : std::vector<std::string>{"joint.0.shear_stiffness=" + ks});
    ASSERT_TRUE(r.run.result.ok) << r.run.result.reason;
    const auto& h = r.run.history;
    const auto& energy = r.run.result.summary["energy"];
    const double work = energy["external_work"].get<double>();
    EXPECT_GT(work, 5000.0) << ks;  // m g sin(th) s = 750 kg x 5 m/s^2 x 1.34 m
    EXPECT_LT(std::abs(energy["unaccounted"].get<double>()), 0.01 * work) << ks;
    EXPECT_EQ(energy["created_by_resolves"].get<double>(), 0.0) << ks;
    for (std::size_t i = 0; i < h.at("time").size(); ++i)
      ASSERT_LT(std::abs(h.at("energy.external_work")[i] - h.at("energy.kinetic")[i] -
                         h.at("energy.strain")[i] - h.at("energy.dissipated")[i]),
                0.01 * work)
          << "ks = " << ks << ", t = " << h.at("time")[i];
    const double t = h.at("time").back();
    EXPECT_NEAR(r.s.back(), frictional_incline_slide(t), 0.01 * frictional_incline_slide(t)) << ks;
  }
}

TEST(FrictionalIncline, SameSlideAtAQuarterOfTheStep) {
  // dt = 1e-2 s and 2.5e-3 s give the same displacement at t = 1 s within 1 % (measured
  // 1.3462 and 1.3439 m, 0.17 %; the finer step is +0.31 % off the closed form: the
  // release, see docs/method-choices.md "Friction with inertia").
  const InclineRun coarse = run_frictional_incline({});
  const InclineRun fine = run_frictional_incline({"time.dt=2.5e-3"});
  ASSERT_TRUE(coarse.run.result.ok) << coarse.run.result.reason;
  ASSERT_TRUE(fine.run.result.ok) << fine.run.result.reason;
  EXPECT_NEAR(coarse.s.back(), fine.s.back(), 0.01 * fine.s.back());
  EXPECT_NEAR(fine.s.back(), frictional_incline_slide(1.0), 0.01 * frictional_incline_slide(1.0));
}

TEST(FrictionalIncline, NewmarkMakesNoEnergyInAStep) {
  // The frictional incline under Newmark's average acceleration at the scene's dt = 10 ms.
  // With the trapezoid on its contact forces a step created up to 28 % of the work and the
  // block was thrown off the slope (11,234 steps, 48.8 % created, u_x 0.96 m). With the mean
  // normal force, friction from it over the whole step and twice the end shear force
  // (docs/method-choices.md, "Newmark and contacts"), measured: 3,069 steps (155 redone by the
  // open-close iteration, none by the energy check), the most a step created 0.03 % of the
  // work and 0.20 % over the run; the slide 2.2 % short of the closed form and 2.5 % of the
  // work lost unbooked (the gaps measured anew at step starts, the release of springs at
  // their start force: open points of issue 30); at dt = 2.5e-3 and 1e-3 -0.3 % and -2.1 %.
  // Required: no step creating more than 1 % of the work and 1 % over the run; the slide
  // within 5 % of the closed form, the velocity along the slope never reversed.
  const InclineRun r = run_frictional_incline({"time.integrator=newmark"});
  ASSERT_TRUE(r.run.result.ok) << r.run.result.reason;
  const auto& summary = r.run.result.summary;
  const double work = summary["energy"]["external_work"].get<double>();
  EXPECT_GT(work, 4000.0);
  EXPECT_LE(summary["energy_check"]["largest_step_created_share"].get<double>(), 0.01);
  EXPECT_LE(summary["energy_check"]["created"].get<double>(), 0.01 * work);
  const double t = r.run.history.at("time").back();
  EXPECT_NEAR(r.s.back(), frictional_incline_slide(t), 0.05 * frictional_incline_slide(t));
  for (std::size_t i = 1; i < r.v.size(); ++i)
    ASSERT_GT(r.v[i], 0.0) << "the block moved up the slope at t = " << r.run.history.at("time")[i];
}

/// A 1 m x 0.5 m block on a 4 m x 1 m base, meshed separately (two blocks), placed `depth`
/// (m) into the base.
std::string block_on_flat_base_geo(double depth = 0.0) {
  return test::block_on_base_geo({0.0, 0.0, 4.0, 1.0, 0.5},
                                 {0.5, 1.0 - depth, 1.5, 1.5 - depth, 0.25});
}

/// The block set off at 2 m/s along the base, joint friction 20 deg, dynamic for 0.8 s.
const std::string kBlockOnBaseScene =
    test::BlockOnBaseScene{
        .plane = "stress",
        .time = "dt = 1e-3\nend = 0.8",
        .friction_angle = 20.0,
        .more = "[[initial]]\nbody = \"block\"\nvelocity = [2.0, 0.0]\n" +
                test::probe_body("block", "block", {"ux", "uy", "vx", "vy", "rotation"}),
        .output = test::no_frames("out")}
        .toml();

TEST(Contact, OverlapNoSolveResistedCarriesNoForceWithoutInertia) {
  // A block starts 10 um deep in its base, at rest, under gravity (docs/method-choices.md,
  // "Unresisted overlap"). Without inertia that overlap is the contacts' zero: the block
  // settles exactly as one placed on the surface does (u_x, u_y of every row within 1e-9 m;
  // measured settlement 2.2e-6 m, the elastic shortening of block and base). A penalty
  // push from the overlap (kn = 20 E t = 2e11 N/m per contact) would lift it by about
  // 1e-5 m. With inertia the push stays: the block leaves the base upwards (largest
  // u_y > 5e-6 m).
  const std::vector<std::string> at_rest = {"initial.0.velocity=[0.0, 0.0]", "time.end=0.005"};
  auto quasi_static = at_rest;
  quasi_static.push_back("scene.analysis=\"quasi-static\"");
  const auto placed = test::run_scene_text(kBlockOnBaseScene, quasi_static, 0,
                                           {{"block_on_base.geo", block_on_flat_base_geo(0.0)}});
  const auto sunk = test::run_scene_text(kBlockOnBaseScene, quasi_static, 0,
                                         {{"block_on_base.geo", block_on_flat_base_geo(1e-5)}});
  ASSERT_TRUE(placed.result.ok) << placed.result.reason;
  ASSERT_TRUE(sunk.result.ok) << sunk.result.reason;
  ASSERT_EQ(placed.history.at("block.uy").size(), sunk.history.at("block.uy").size());
  EXPECT_LT(placed.history.at("block.uy").back(), -1e-6);  // it did settle
  for (const char* column : {"block.ux", "block.uy"})
    for (std::size_t i = 0; i < sunk.history.at(column).size(); ++i)
      EXPECT_NEAR(sunk.history.at(column)[i], placed.history.at(column)[i], 1e-9)
          << column << " row " << i;

  const auto pushed = test::run_scene_text(kBlockOnBaseScene, at_rest, 0,
                                           {{"block_on_base.geo", block_on_flat_base_geo(1e-5)}});
  ASSERT_TRUE(pushed.result.ok) << pushed.result.reason;
  const auto& uy = pushed.history.at("block.uy");
  EXPECT_GT(*std::max_element(uy.begin(), uy.end()), 5e-6);
}

TEST(Friction, BrakesABlockSlidingOnAFlatBase) {
  // v0 = 2 m/s, mu = tan 20 deg: the block decelerates at mu g and stops after
  // v0 / (mu g) = 0.549 s at v0^2 / (2 mu g) = 0.549 m; within 2 % (measured +0.5 %).
  // Without friction it keeps v0 (checked to 1e-5 m/s).
  const double mu = std::tan(20.0 * std::numbers::pi / 180.0), g = 10.0, v0 = 2.0;
  const auto run = test::run_scene_text(kBlockOnBaseScene, {}, 0,
                                        {{"block_on_base.geo", block_on_flat_base_geo()}});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& t = run.history.at("time");
  const auto& vx = run.history.at("block.vx");
  std::size_t stop = 0;
  while (stop < vx.size() && vx[stop] > 1e-3) ++stop;
  ASSERT_LT(stop, vx.size()) << "the block never stops";
  EXPECT_NEAR(t[stop], v0 / (mu * g), 0.02 * v0 / (mu * g));
  EXPECT_NEAR(run.history.at("block.ux").back(), v0 * v0 / (2 * mu * g),
              0.02 * v0 * v0 / (2 * mu * g));
  EXPECT_LT(std::abs(vx.back()), 1e-3);  // and stays stopped
  // Friction dissipated the block's kinetic energy, 1/2 m v0^2 = 2600 J (m = 1300 kg per
  // metre of thickness): energy.dissipated within 2 % (measured 2594.6 J, -0.2 %), and
  // kinetic + strain + dissipated = initial kinetic + external work within 1 % (measured
  // -0.2 %: DDA's own damping).
  const auto& dissipated = run.history.at("energy.dissipated");
  const double kinetic0 = 0.5 * 1300.0 * v0 * v0;
  EXPECT_NEAR(dissipated.back(), kinetic0, 0.02 * kinetic0);
  EXPECT_NEAR(run.history.at("energy.kinetic").back() + run.history.at("energy.strain").back() +
                  dissipated.back(),
              kinetic0 + run.history.at("energy.external_work").back(), 0.01 * kinetic0);

  const auto free = test::run_scene_text(kBlockOnBaseScene, {"joint.0.friction_angle=0"}, 0,
                                         {{"block_on_base.geo", block_on_flat_base_geo()}});
  ASSERT_TRUE(free.result.ok) << free.result.reason;
  EXPECT_NEAR(free.history.at("block.vx").back(), v0, 1e-5);
  EXPECT_NEAR(free.history.at("block.ux").back(), v0 * 0.8, 1e-5);
}

/// A 1 m x 0.5 m block glued under a fixed 4 m x 1 m ledge.
std::string hanging_block_geo() {
  return test::rectangle_geo(0, 0.0, 0.0, 4.0, 1.0, 0.5) +
         test::rectangle_geo(10, 1.5, -0.5, 2.5, 0.0, 0.25) +
         "Physical Surface(\"ledge\") = {1};\nPhysical Surface(\"block\") = {11};\n"
         "Physical Curve(\"ledge_top\") = {3};\n";
}

TEST(Joints, BondWithTensileStrengthHoldsAHangingBlockUntilTooWeak) {
  // The block (13 kN) hangs from a bonded joint 1 m long: the mean tension is 13 kPa, and
  // the release doubles it for a moment. With tensile strength and cohesion 5 x 13 kPa the
  // bond holds (the block moves less than 1e-5 m); at 0.5 x 13 kPa it breaks and the block
  // falls freely: u_y = -1/2 g t^2 within 0.1 %.
  const std::string scene = test::scene_table("hanging", "dynamic", "gravity = [0.0, -10.0]\n") +
                            "[time]\ndt = 1e-3\nend = 0.3\n[mesh]\ngeo = \"hanging.geo\"\n" +
                            test::material("*", 2600.0, 10e9, 0.25) +
                            test::joint("ledge", "block", 30.0) + test::fixed("ledge_top") +
                            test::probe_body("block", "block", {"uy"}) + test::no_frames("out");
  const auto strong =
      test::run_scene_text(scene, {"joint.0.tensile_strength=65e3", "joint.0.cohesion=65e3"}, 0,
                           {{"hanging.geo", hanging_block_geo()}});
  ASSERT_TRUE(strong.result.ok) << strong.result.reason;
  EXPECT_LT(std::abs(strong.history.at("block.uy").back()), 1e-5);
  const auto weak =
      test::run_scene_text(scene, {"joint.0.tensile_strength=6.5e3", "joint.0.cohesion=6.5e3"}, 0,
                           {{"hanging.geo", hanging_block_geo()}});
  ASSERT_TRUE(weak.result.ok) << weak.result.reason;
  EXPECT_NEAR(weak.history.at("block.uy").back(), -0.5 * 10.0 * 0.09, 0.001 * 0.45);
}

}  // namespace
}  // namespace rockdd

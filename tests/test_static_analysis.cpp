// Static analysis through the whole pipeline (scene -> Gmsh -> model -> CHOLMOD -> outputs),
// checked against closed-form elasticity. Constant-stress fields are reproduced exactly by
// CST elements on any mesh (the patch test), so these tolerances are round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace rockdd {
namespace {

// A 2 m x 1 m plate on an unstructured mesh: left edge on rollers (x fixed), the
// bottom-left corner pinned, pulled on the right by a total force F.
std::string uniaxial_plate(const std::string& plane, double poisson) {
  return R"(
[scene]
name = "uniaxial"
analysis = "static"
plane = ")" +
         plane + R"("
thickness = 0.5
[mesh]
shape = "rectangle"
size = [2.0, 1.0]
element_size = 0.13
[[material]]
body = "body"
density = 2500.0
young = 40e9
poisson = )" +
         std::to_string(poisson) + R"(
[[boundary]]
on = "left"
fix = ["x"]
[[boundary]]
on = "bottom_left"
fix = ["x", "y"]
[[load]]
on = "right"
force = [1e6, 0.0]
[[probe]]
name = "right"
on = "right"
fields = ["ux", "uy"]
[[probe]]
name = "left"
on = "left"
fields = ["fx", "fy"]
[output]
every = 0
)";
}

using test::run_scene_text;
using StaticRun = test::SceneRun;

TEST(PatchTest, UniaxialTensionPlaneStressIsExactOnAnUnstructuredMesh) {
  // sigma_xx = F / (h t) = 1e6 / (1 * 0.5) = 2 MPa in every element; sigma_yy = sigma_xy = 0.
  // u_x(right) = sigma L / E, u_y = -nu sigma y / E (plane stress).
  const double nu = 0.25, E = 40e9, sigma = 2e6;
  const StaticRun run = run_scene_text(uniaxial_plate("stress", nu));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  for (std::int32_t e = 0; e < run.model.num_elements(); ++e) {
    EXPECT_NEAR(run.model.stress[3 * e], sigma, 1e-9 * sigma);
    EXPECT_NEAR(run.model.stress[3 * e + 1], 0.0, 1e-9 * sigma);
    EXPECT_NEAR(run.model.stress[3 * e + 2], 0.0, 1e-9 * sigma);
  }
  for (std::int32_t n = 0; n < run.model.num_nodes(); ++n) {
    EXPECT_NEAR(run.model.u[2 * n], sigma * run.model.X[2 * n] / E, 1e-12);
    EXPECT_NEAR(run.model.u[2 * n + 1], -nu * sigma * run.model.X[2 * n + 1] / E, 1e-12);
  }
  EXPECT_NEAR(run.history.at("right.ux").back(), sigma * 2.0 / E, 1e-15);
  // The left support pulls back with the applied force.
  EXPECT_NEAR(run.history.at("left.fx").back(), -1e6, 1e-6);
  EXPECT_NEAR(run.history.at("left.fy").back(), 0.0, 1e-6);
}

TEST(PatchTest, UniaxialStressInPlaneStrainUsesTheStiffenedModulus) {
  // Plane strain with sigma_yy = 0: eps_xx = (1 - nu^2) sigma / E, eps_yy = -nu (1 + nu) sigma / E.
  const double nu = 0.3, E = 40e9, sigma = 2e6;
  const StaticRun run = run_scene_text(uniaxial_plate("strain", nu));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  for (std::int32_t e = 0; e < run.model.num_elements(); ++e) {
    EXPECT_NEAR(run.model.strain[3 * e], (1 - nu * nu) * sigma / E, 1e-9 * sigma / E);
    EXPECT_NEAR(run.model.strain[3 * e + 1], -nu * (1 + nu) * sigma / E, 1e-9 * sigma / E);
  }
}

TEST(PatchTest, NearlyIncompressiblePlaneStrainStaysFinite) {
  // nu = 0.4999: CST locks in bending, but a uniaxial constant-stress field is still exact.
  const StaticRun run = run_scene_text(uniaxial_plate("strain", 0.4999));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  for (std::int32_t e = 0; e < run.model.num_elements(); ++e)
    EXPECT_NEAR(run.model.stress[3 * e], 2e6, 1e-6 * 2e6);
}

TEST(StaticAnalysis, ClapeyronStrainEnergyEqualsExternalWork) {
  // A linear static step from rest: W_ext = 1/2 F.u = U_strain.
  const StaticRun run = run_scene_text(uniaxial_plate("stress", 0.25));
  const double strain = run.history.at("energy.strain").back();
  EXPECT_GT(strain, 0.0);
  EXPECT_NEAR(run.history.at("energy.external_work").back(), strain, 1e-9 * strain);
  // And it equals sigma^2 V / (2E) = (2e6)^2 * (2 * 1 * 0.5) / (2 * 40e9) = 50 J.
  EXPECT_NEAR(strain, 50.0, 1e-8);
}

TEST(StaticAnalysis, HydrostaticPressureGivesUniformStress) {
  // Pressure p on every side: sigma_xx = sigma_yy = -p everywhere (compression negative).
  const std::string text = R"(
[scene]
name = "hydrostatic"
analysis = "static"
[mesh]
shape = "rectangle"
size = [1.0, 1.0]
element_size = 0.15
[[material]]
body = "*"
density = 2000.0
young = 10e9
poisson = 0.2
[[boundary]]
on = "bottom_left"
fix = ["x", "y"]
[[boundary]]
on = "bottom_right"
fix = ["y"]
[[load]]
on = "left"
pressure = 5e6
[[load]]
on = "right"
pressure = 5e6
[[load]]
on = "top"
pressure = 5e6
[[load]]
on = "bottom"
pressure = 5e6
[output]
every = 0
)";
  const StaticRun run = run_scene_text(text);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  for (std::int32_t e = 0; e < run.model.num_elements(); ++e) {
    EXPECT_NEAR(run.model.stress[3 * e], -5e6, 1e-6);
    EXPECT_NEAR(run.model.stress[3 * e + 1], -5e6, 1e-6);
    EXPECT_NEAR(run.model.stress[3 * e + 2], 0.0, 1e-6);
  }
}

TEST(StaticAnalysis, SelfWeightReactionEqualsTheWeight) {
  // Column 1 m x 4 m under gravity on a fixed base: the base pushes up with rho g A t.
  const std::string text = R"(
[scene]
name = "column"
analysis = "static"
gravity = [0.0, -9.81]
thickness = 2.0
[mesh]
shape = "rectangle"
size = [1.0, 4.0]
divisions = [5, 20]
[[material]]
body = "body"
density = 2700.0
young = 50e9
poisson = 0.2
[[boundary]]
on = "bottom"
fix = ["x", "y"]
[[probe]]
name = "base"
on = "bottom"
fields = ["fx", "fy"]
[output]
every = 0
)";
  const StaticRun run = run_scene_text(text);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  EXPECT_NEAR(run.history.at("base.fy").back(), 2700.0 * 9.81 * 4.0 * 2.0, 1e-6);
  EXPECT_NEAR(run.history.at("base.fx").back(), 0.0, 1e-6);
}

TEST(StaticAnalysis, LoadStepsRampTheLoadLinearly) {
  // steps = 4: load factor n/4, so the tip displacement grows in four equal increments.
  const StaticRun run = run_scene_text(uniaxial_plate("stress", 0.25) + "[time]\nsteps = 4\n");
  ASSERT_EQ(run.history.at("right.ux").size(), 5u);
  for (int n = 0; n <= 4; ++n)
    EXPECT_NEAR(run.history.at("right.ux")[n], n / 4.0 * 2e6 * 2.0 / 40e9, 1e-15);
}

TEST(StaticAnalysis, ImposedVelocityMovesTheBoundaryEachStep) {
  // Displacement control: the right edge moves by v dt per step; after 5 steps of 0.1 s at
  // 1e-4 m/s it has moved 5e-5 m and the reaction is E eps h t = 40e9 * 2.5e-5 * 1 * 0.5.
  std::string text = uniaxial_plate("stress", 0.25);
  text.replace(text.find("[[load]]"), text.find("[[probe]]") - text.find("[[load]]"),
               "[[boundary]]\non = \"right\"\nvelocity_x = 1e-4\n");
  text.replace(text.find("name = \"right\"\non = \"right\"\nfields = [\"ux\", \"uy\"]"),
               std::string("name = \"right\"\non = \"right\"\nfields = [\"ux\", \"uy\"]").size(),
               "name = \"right\"\non = \"right\"\nfields = [\"ux\", \"fx\"]");
  const StaticRun run = run_scene_text(text + "[time]\ndt = 0.1\nsteps = 5\n");
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  EXPECT_NEAR(run.history.at("right.ux").back(), 5e-5, 1e-15);
  EXPECT_NEAR(run.history.at("right.fx").back(), 40e9 * 2.5e-5 * 0.5, 1e-3);
  EXPECT_NEAR(run.history.at("left.fx").back(), -40e9 * 2.5e-5 * 0.5, 1e-3);
}

TEST(StaticAnalysis, UnrestrainedBlockIsRejectedNamingIt) {
  std::string text = uniaxial_plate("stress", 0.25);
  text.replace(text.find("fix = [\"x\", \"y\"]"), 16, "fix = [\"x\"]");
  test::TempDir dir;
  Scene scene = test::scene_from_text(text, dir.path());
  try {
    Simulation sim(scene, build_scene_model(scene));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("block 0 (body 'body') is free in y translation"),
              std::string::npos)
        << e.what();
  }
}

TEST(StaticAnalysis, StiffnessContrastOfOneMillionStaysAccurate) {
  // Two conformal layers in series under uniaxial stress, E1 / E2 = 1e6: each layer strains
  // by sigma / E_i exactly (the patch test holds per material).
  const std::string layers_geo = R"(
Point(1) = {0, 0, 0, 0.1}; Point(2) = {1, 0, 0, 0.1}; Point(3) = {2, 0, 0, 0.1};
Point(4) = {2, 1, 0, 0.1}; Point(5) = {1, 1, 0, 0.1}; Point(6) = {0, 1, 0, 0.1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
Physical Surface("soft") = {1}; Physical Surface("stiff") = {2};
Physical Curve("left") = {6}; Physical Curve("right") = {3}; Physical Point("origin") = {1};
)";
  const std::string text = R"(
[scene]
name = "contrast"
analysis = "static"
[mesh]
geo = "layers.geo"
[[material]]
body = "soft"
density = 1000.0
young = 1e4
poisson = 0.0
[[material]]
body = "stiff"
density = 1000.0
young = 1e10
poisson = 0.0
[[boundary]]
on = "left"
fix = ["x"]
[[boundary]]
on = "origin"
fix = ["x", "y"]
[[load]]
on = "right"
force = [1.0, 0.0]
[[probe]]
name = "right"
on = "right"
fields = ["ux"]
[output]
every = 0
)";
  const StaticRun run = run_scene_text(text, {}, 0, {{"layers.geo", layers_geo}});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& history = run.history;
  // u(right) = sigma (1/E_soft + 1/E_stiff) with sigma = 1 Pa and each layer 1 m long.
  // The contrast multiplies the condition number by 1e6, so round-off grows to about
  // 1e-8 relative; 1e-7 still resolves the stiff layer's 1e-10 m share to 10 %.
  EXPECT_NEAR(history.at("right.ux").back(), 1.0 / 1e4 + 1.0 / 1e10, 1e-7 * 1e-4);
}

TEST(Determinism, HistoryIsIdenticalForOneAndTwoThreads) {
  const std::string text = uniaxial_plate("stress", 0.25) + "[time]\nsteps = 3\n";
  test::TempDir dir;
  Scene scene = test::scene_from_text(text, dir.path(), {"mesh.element_size=0.03"});
  std::string history[2];
  for (int threads = 1; threads <= 2; ++threads) {
    Simulation sim(scene, build_scene_model(scene));
    RunOptions options;
    options.out_root = dir.path() / ("out" + std::to_string(threads));
    options.threads = threads;
    ASSERT_TRUE(sim.run(options).ok);
    history[threads - 1] = test::read_text(options.out_root / "uniaxial" / "history.csv");
  }
  EXPECT_EQ(history[0], history[1]);
}

}  // namespace
}  // namespace rockdd

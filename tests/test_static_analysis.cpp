// Static analysis through the whole pipeline (scene -> Gmsh -> model -> CHOLMOD -> outputs),
// checked against closed-form elasticity. Constant-stress fields are reproduced exactly by
// CST elements on any mesh (the patch test), so these tolerances are round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "support/end_loaded_plate.hpp"
#include "support/file_text.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

// The 2 m x 1 m end-loaded plate (test::EndLoadedPlate: E = 40 GPa, 0.5 m thick, pulled on the
// right by F = 1e6 N) with probes of its right end's displacement and the left support's reaction.
std::string uniaxial_plate(const std::string& plane, double poisson) {
  return test::EndLoadedPlate{.plane = plane,
                              .poisson = poisson,
                              .probes = test::probe_on("right", "right", {"ux", "uy"}) +
                                        test::probe_on("left", "left", {"fx", "fy"})}
      .toml();
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
  std::string text = test::scene_table("hydrostatic", "static") +
                     test::rectangle_mesh(1.0, 1.0, 0.15) + test::material("*", 2000.0, 10e9, 0.2) +
                     test::fixed("bottom_left") + test::fixed("bottom_right", {"y"});
  for (const std::string side : {"left", "right", "top", "bottom"})
    text += "[[load]]\non = \"" + side + "\"\npressure = 5e6\n";
  const StaticRun run = run_scene_text(text + test::no_frames());
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  for (std::int32_t e = 0; e < run.model.num_elements(); ++e) {
    EXPECT_NEAR(run.model.stress[3 * e], -5e6, 1e-6);
    EXPECT_NEAR(run.model.stress[3 * e + 1], -5e6, 1e-6);
    EXPECT_NEAR(run.model.stress[3 * e + 2], 0.0, 1e-6);
  }
}

TEST(StaticAnalysis, SelfWeightReactionEqualsTheWeight) {
  // Column 1 m x 4 m under gravity on a fixed base: the base pushes up with rho g A t.
  const std::string text =
      test::scene_table("column", "static", "gravity = [0.0, -9.81]\nthickness = 2.0\n") +
      test::rectangle_mesh(1.0, 4.0, {5, 20}) + test::material("body", 2700.0, 50e9, 0.2) +
      test::fixed("bottom") + test::probe_on("base", "bottom", {"fx", "fy"}) + test::no_frames();
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
  const test::EndLoadedPlate plate{.loading = "[[boundary]]\non = \"right\"\nvelocity_x = 1e-4\n",
                                   .probes = test::probe_on("right", "right", {"ux", "fx"}) +
                                             test::probe_on("left", "left", {"fx", "fy"})};
  const StaticRun run = run_scene_text(plate.toml() + "[time]\ndt = 0.1\nsteps = 5\n");
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
  const std::string text =
      test::scene_table("contrast", "static") + "[mesh]\ngeo = \"layers.geo\"\n" +
      test::material("soft", 1000.0, 1e4, 0.0) + test::material("stiff", 1000.0, 1e10, 0.0) +
      test::fixed("left", {"x"}) + test::fixed("origin") +
      "[[load]]\non = \"right\"\nforce = [1.0, 0.0]\n" + test::probe_on("right", "right", {"ux"}) +
      test::no_frames();
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
    const auto out = dir.path() / ("out" + std::to_string(threads));
    ASSERT_TRUE(test::run_scene(scene, out, threads).result.ok);
    history[threads - 1] = test::read_text(out / "out" / "uniaxial" / "history.csv");
  }
  EXPECT_EQ(history[0], history[1]);
}

}  // namespace
}  // namespace rockdd

// From continuum to discontinuum (METHOD.md "Heterogeneity", "Elastic damage", "Fracture"):
// Weibull specimens, the damage iteration and detachment of damaged elements into blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "engine/contact/contact_detection.hpp"
#include "engine/damage/damage_stage.hpp"
#include "engine/damage/detachment.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

/// A 0.1 m x 0.05 m bar pulled at its right end (uniaxial tension, quasi-static).
/// E = 20 GPa, ft = 2 MPa; the right end moves 5e-7 m a step of 1 s, to t = 12 s. `extra`
/// follows the material's keys (heterogeneity, detachment, and tables after them).
std::string bar_in_tension(const std::string& extra) {
  return test::scene_table("bar", "quasi-static") + "[time]\ndt = 1.0\nend = 12.0\n" +
         test::rectangle_mesh(0.1, 0.05, {20, 10}) +
         test::material("*", 2700.0, 20e9, 0.2,
                        "tensile_strength = 2e6\nfriction_angle = 30.0\n" + extra) +
         test::fixed("left", {"x"}) + "[[boundary]]\non = \"bottom\"\nvelocity_y = 0.0\n" +
         "[[boundary]]\non = \"right\"\nvelocity_x = 5e-7\n" +
         test::probe_on("right", "right", {"fx"}) + test::no_frames("out");
}

TEST(Heterogeneity, TheSeedFixesTheSpecimen) {
  // Weibull m = 1.5 draws of E and ft over 10^4 elements: the same seed gives the same
  // specimen bit for bit, another seed another one; sample means within 3 % of the scene's
  // (the standard error of the mean is 0.7 % for m = 1.5).
  const std::string text =
      test::scene_table("specimen", "static") + test::rectangle_mesh(1.0, 0.5, {100, 50}) +
      test::material("*", 2700.0, 50e9, 0.2,
                     "tensile_strength = 7e6\nhomogeneity = 1.5\n"
                     "heterogeneous = [\"young\", \"tensile_strength\"]\nseed = 42\n") +
      test::fixed("bottom");
  test::TempDir dir;
  const Scene scene = test::scene_from_text(text, dir.path());
  const Model a = build_scene_model(scene), b = build_scene_model(scene);
  EXPECT_EQ(a.young, b.young);
  EXPECT_EQ(a.tensile_strength, b.tensile_strength);
  const Scene other = test::scene_from_text(text, dir.path(), {"material.0.seed=43"});
  EXPECT_NE(build_scene_model(other).tensile_strength, a.tensile_strength);
  const double n = static_cast<double>(a.young.size());
  EXPECT_NEAR(std::accumulate(a.young.begin(), a.young.end(), 0.0) / n, 50e9, 0.03 * 50e9);
  EXPECT_NEAR(std::accumulate(a.tensile_strength.begin(), a.tensile_strength.end(), 0.0) / n, 7e6,
              0.03 * 7e6);
}

TEST(Damage, FirstElementDamagesWhenTheStressReachesTheWeakestStrength) {
  // Uniform tension sigma = F / A (A = 0.05 m x 1 m): with Weibull ft (m = 10) the first
  // element damages in the step where sigma first reaches min_e ft_e (stress onset): the
  // stress one step earlier is below it, the stress of that step at or above it.
  const auto run = test::run_scene_text(
      bar_in_tension("homogeneity = 10.0\nheterogeneous = [\"tensile_strength\"]\nseed = 7\n"));
  const auto& fx = run.history.at("right.fx");
  test::TempDir dir;
  const Scene scene = test::scene_from_text(
      bar_in_tension("homogeneity = 10.0\nheterogeneous = [\"tensile_strength\"]\nseed = 7\n"),
      dir.path());
  const Model fresh = build_scene_model(scene);
  const double weakest =
      *std::min_element(fresh.tensile_strength.begin(), fresh.tensile_strength.end());
  // The first row whose stress reaches the weakest strength is where damage must start.
  std::size_t first = 0;
  while (first < fx.size() && fx[first] / 0.05 < weakest) ++first;
  ASSERT_LT(first, fx.size()) << "the load never reached the weakest strength";
  ASSERT_GE(first, 2u);
  // Stopped one step short of it, nothing is damaged; stopped at it, the weakest element is.
  const std::string heterogeneous =
      "homogeneity = 10.0\nheterogeneous = [\"tensile_strength\"]\nseed = 7\n"
      "detach_at_damage = 0.0\n";  // detached at onset: the damaged element is a block
  const auto before = test::run_scene_text(bar_in_tension(heterogeneous),
                                           {"time.end=" + std::to_string(first - 1) + ".0"});
  EXPECT_EQ(before.result.summary["damaged_elements"].get<long>(), 0);
  const auto at = test::run_scene_text(bar_in_tension(heterogeneous),
                                       {"time.end=" + std::to_string(first) + ".0"});
  EXPECT_GE(at.result.summary["damaged_elements"].get<long>(), 1);
  EXPECT_GE(at.result.summary["detached_elements"].get<long>(), 1);
  EXPECT_GE(at.result.summary["blocks"].get<long>(), 2);
}

TEST(Damage, DissipatesWhatTheSecantLawCannotReturn) {
  // Homogeneous bar in uniaxial tension, 4.7e-6 strain a step, elements kept attached
  // (detach_at_damage = 0.99: eq. 3 stays below 1 - lambda / eta = 0.98 until eps_tu =
  // 5e-4). Every element passes the onset in the same step (eps_1 = 22 x 4.7e-6, 3 % past
  // eps_t0 = 1e-4: smaller steps let round-off pick one element, which localizes). Eq. (3)
  // unloads to the origin, so growing w from w' to w at strain eps releases
  // 1/2 (w - w') E0 eps^2 per unit volume for good:
  // - energy.dissipated = V sum_k 1/2 E0 eps_k^2 (w_k - w_{k-1}), w_k = 1 - lambda eps_t0 /
  //   eps_k, to 1e-9;
  // - and the integral from the onset, V [1/2 E0 eps_1^2 w_1 + 1/2 lambda E0 eps_t0 (eps -
  //   eps_1)] (the plateau sigma = lambda ft0 dissipates lambda ft0 / 2 per unit strain),
  //   within 0.5 %;
  // - the balance external work = strain + dissipated, to the error of the trapezoidal rule
  //   that integrates the work: across the onset's force drop 1/2 (E0 eps_1 - lambda ft0)
  //   4.7e-6 V, plus the elastic rise before each step's damage update on the plateau (6 % of
  //   that): within 1.1 x the first.
  // The steps are not cut at the onset (fracture.locate_onsets = false): the sums above are
  // over whole steps, and a step cut at the onset lets round-off pick one element.
  const double young = 20e9, ft0 = 2e6, eps_t0 = ft0 / young, lambda = 0.1, rate = 4.7e-6;
  const int steps = 40;
  const auto run = test::run_scene_text(
      bar_in_tension("detach_at_damage = 0.99\n"),
      {"boundary.2.velocity_x=4.7e-7", "time.end=" + std::to_string(steps) + ".0",
       "fracture.locate_onsets=false"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  EXPECT_EQ(run.result.summary["detached_elements"].get<long>(), 0);
  const double volume = 0.1 * 0.05;
  double expected = 0.0, w_previous = 0.0, eps_1 = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double eps = rate * k;
    if (eps * young < ft0) continue;
    if (eps_1 == 0.0) eps_1 = eps;
    const double w = 1.0 - lambda * eps_t0 / eps;
    expected += 0.5 * (w - w_previous) * young * eps * eps * volume;
    w_previous = w;
  }
  const auto& dissipated = run.history.at("energy.dissipated");
  EXPECT_NEAR(dissipated.back(), expected, 1e-9 * expected);
  const double eps = steps * rate;
  const double integral = volume * (0.5 * young * eps_1 * eps_1 * (1.0 - lambda * eps_t0 / eps_1) +
                                    0.5 * lambda * young * eps_t0 * (eps - eps_1));
  EXPECT_NEAR(dissipated.back(), integral, 0.005 * integral);
  const double stored = run.history.at("energy.strain").back();
  EXPECT_NEAR(run.history.at("energy.external_work").back(), stored + dissipated.back(),
              1.1 * 0.5 * (young * eps_1 - lambda * ft0) * rate * volume);
  // summary.json splits the same balance: all of it damage (no contacts, no fragments to
  // anchor), and "unaccounted" is exactly the trapezoidal rule's share above.
  const auto& energy = run.result.summary.at("energy");
  EXPECT_NEAR(energy.at("damage_dissipation").get<double>(), dissipated.back(), 1e-12 * expected);
  EXPECT_EQ(energy.at("friction_dissipation").get<double>(), 0.0);
  EXPECT_EQ(energy.at("anchor_work").get<double>(), 0.0);
  EXPECT_NEAR(energy.at("unaccounted").get<double>(),
              run.history.at("energy.external_work").back() - stored - dissipated.back() -
                  run.history.at("energy.kinetic").back(),
              1e-9 * expected);
}

TEST(Fracture, SameSeedSameHistoryWhateverTheThreads) {
  // The bar cracks through (Weibull ft, m = 10, seed 7: damage from t = 11 s, the load
  // drops from 70 kN to a few kN by t = 13 s): damage, detachment, regrouping and the
  // crack contacts must give the same history.csv values, bit for bit, on 1 and 2 threads.
  const std::string scene =
      bar_in_tension("homogeneity = 10.0\nheterogeneous = [\"tensile_strength\"]\nseed = 7\n");
  const auto one = test::run_scene_text(scene, {"time.end=16.0"}, 1);
  const auto two = test::run_scene_text(scene, {"time.end=16.0"}, 2);
  ASSERT_TRUE(one.result.ok) << one.result.reason;
  ASSERT_TRUE(two.result.ok) << two.result.reason;
  EXPECT_GT(one.result.summary["detached_elements"].get<long>(), 10);
  EXPECT_EQ(one.history, two.history);
  EXPECT_EQ(one.model.damage, two.model.damage);
}

TEST(Fracture, SplittingConservesMassAndMomentum) {
  // Detaching elements splits nodes: total mass and momentum are unchanged to round-off
  // (1e-12 relative), copies keep their node's displacement and velocity, and each lone
  // detached element is a block of its own.
  test::TempDir dir;
  const Scene scene = test::scene_from_text(bar_in_tension(""), dir.path());
  Model model = build_scene_model(scene);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (double& v : model.v) v = U(rng);
  for (double& u : model.u) u = 1e-6 * U(rng);
  auto totals = [](const Model& m) {
    double mass = 0, px = 0, py = 0;
    for (std::int32_t n = 0; n < m.num_nodes(); ++n) {
      mass += m.node_mass[n];
      px += m.node_mass[n] * m.v[2 * n];
      py += m.node_mass[n] * m.v[2 * n + 1];
    }
    return std::array<double, 3>{mass, px, py};
  };
  const auto before = totals(model);
  const std::int32_t nodes_before = model.num_nodes();
  for (const std::int32_t e : {37, 120, 255}) model.damage[e] = 0.9;  // far apart
  std::vector<std::uint8_t> detached;
  const std::vector<double> threshold(static_cast<std::size_t>(model.num_elements()), 0.0);
  const Detachment d = detach_damaged_elements(model, threshold, detached);
  EXPECT_EQ(d.detached, 3);
  EXPECT_EQ(model.num_blocks, 4);
  EXPECT_GT(model.num_nodes(), nodes_before);
  const auto after = totals(model);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(after[i], before[i], 1e-12 * std::abs(before[0]));
  for (std::int32_t n = 0; n < model.num_nodes(); ++n)
    for (int c = 0; c < 2; ++c) EXPECT_EQ(model.X[2 * n + c], model.X[2 * d.node_origin[n] + c]);
  // Detaching again with nothing new changes nothing.
  EXPECT_EQ(detach_damaged_elements(model, threshold, detached).detached, 0);
}

TEST(Fracture, TheKeptAdjacencyGivesTheContactBoundaryOfTheSplitMesh) {
  // The simulation keeps one edge adjacency through its detachments (drop_split_edges) and
  // builds each new contact stage's block boundary from it: the boundary must be the one a
  // fresh sort of the split connectivity gives, edge for edge, after every detachment.
  test::TempDir dir;
  const Scene scene = test::scene_from_text(bar_in_tension(""), dir.path());
  Model model = build_scene_model(scene);
  EdgeAdjacency kept = build_edge_adjacency(model.conn, "test");
  std::vector<std::uint8_t> detached;
  const std::vector<double> threshold(static_cast<std::size_t>(model.num_elements()), 0.0);
  for (const std::vector<std::int32_t>& wave :
       {std::vector<std::int32_t>{37, 120, 255}, std::vector<std::int32_t>{36, 38, 121, 300}}) {
    for (const std::int32_t e : wave) model.damage[e] = 0.9;
    ASSERT_GT(detach_damaged_elements(model, threshold, detached, kept).detached, 0);
    const BlockBoundary fresh = extract_block_boundary(model);
    const BlockBoundary from_kept = extract_block_boundary(model, kept);
    EXPECT_EQ(from_kept.edge_nodes, fresh.edge_nodes);
    EXPECT_EQ(from_kept.edge_element, fresh.edge_element);
    EXPECT_EQ(from_kept.edge_block, fresh.edge_block);
    EXPECT_EQ(from_kept.vertices, fresh.vertices);
    EXPECT_GT(fresh.edge_element.size(), 0U);
  }
}

}  // namespace
}  // namespace rockdd

namespace rockdd {
namespace {

TEST(DamageEvents, OnlyTheMostOverstressedElementsStartDamageInOnePass) {
  // DamageStage::evaluate starts damage only in elements whose onset ratio (s1 / ft0 here) is
  // >= max / (1 + band); the others past their onset are deferred to the next pass. Two
  // elements of a 1 x 1 rectangle at s1 = 1.2 ft and 1.1 ft: band 0.005 damages the first
  // alone (1.2 / 1.005 > 1.1), band 0.1 both (1.2 / 1.1 = 1.09 < 1.1). Damage of an element
  // already damaged grows whatever the band.
  test::TempDir dir;
  const Scene scene = test::scene_from_text(
      test::scene_table("two", "quasi-static") + "[time]\ndt = 1.0\nsteps = 1\n" +
          test::rectangle_mesh(0.1, 0.1, {1, 1}) +
          test::material("", 2700.0, 20e9, 0.2, "tensile_strength = 2e6\n") + test::fixed("left"),
      dir.path());
  const double ft = 2e6, young = 20e9;
  auto load = [&](Model& model, double s0, double s1) {
    const double s[2] = {s0, s1};
    for (int e = 0; e < 2; ++e) {
      const double sig = s[e] * (1.0 - model.damage[e]);
      model.stress[3 * e] = sig;
      model.stress[3 * e + 1] = model.stress[3 * e + 2] = 0.0;
      model.strain[3 * e] = s[e] / young;
      model.strain[3 * e + 1] = -0.2 * s[e] / young;
      model.strain[3 * e + 2] = 0.0;
    }
  };
  for (const auto& [band, expected] : std::vector<std::pair<double, int>>{{0.005, 1}, {0.1, 2}}) {
    Model model = build_scene_model(scene);
    ASSERT_EQ(model.num_elements(), 2);
    DamageStage stage(scene, model);
    load(model, 1.2 * ft, 1.1 * ft);
    const DamageChange change = stage.evaluate(model, band);
    EXPECT_EQ(change.newly_damaged, expected) << "band " << band;
    EXPECT_EQ(change.deferred, 2 - expected) << "band " << band;
    EXPECT_GT(model.damage[0], 0.0);
    EXPECT_EQ(model.damage[1] > 0.0, expected == 2);
    if (expected == 1) {
      // Next pass: the first element strained further grows even though the second now leads.
      const double w0 = model.damage[0];
      load(model, 3.0 * ft, 1.1 * ft);
      const DamageChange next = stage.evaluate(model, band);
      EXPECT_GT(model.damage[0], w0);
      EXPECT_EQ(next.newly_damaged, 1);
      EXPECT_EQ(next.grown, 2);
    }
  }
}

TEST(Fracture, CrackJointSpringsSetTheContactStiffness) {
  // docs/scene.md: a [[joint]]'s normal_stiffness (N/m per unit thickness) sets kn, the crack joint
  // included (it was ignored: fracture faces took 20 E t whatever the scene said). The bar
  // breaks in the last steps; its fracture faces then use the crack joint's springs.
  const auto run = test::run_scene_text(
      bar_in_tension("homogeneity = 10.0\nheterogeneous = [\"tensile_strength\"]\nseed = 7\n"
                     "detach_at_damage = 0.0\n[[joint]]\nbetween = \"crack\"\n"
                     "friction_angle = 30.0\nnormal_stiffness = 3e9\nshear_stiffness = 1e9\n"),
      {"time.end=40.0"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  ASSERT_GT(run.result.summary["detached_elements"].get<long>(), 0);
  const auto& defaults = run.result.summary["defaults"];
  EXPECT_DOUBLE_EQ(defaults["contact.normal_stiffness"].get<double>(), 3e9);
  EXPECT_DOUBLE_EQ(defaults["contact.shear_stiffness"].get<double>(), 1e9);
}

}  // namespace
}  // namespace rockdd

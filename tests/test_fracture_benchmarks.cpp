// The paper's fracture benchmarks (METHOD.md "The paper's benchmarks"): the flattened
// Brazilian disk to failure (paper section 3.3, Fig. 11), on a coarser mesh than data/'s
// (element size 1.25 mm: about 3,100 elements instead of 18,000).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "support/data_file.hpp"
#include "support/file_text.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"

namespace rockdd {
namespace {

constexpr double kRadius = 0.025, kFlatHalfAngle = 10.0 * std::numbers::pi / 180.0;

/// Load P (N, per unit thickness) of a pressure p on each flat: P = p 2 R sin(alpha).
double flat_load(double pressure) {
  return pressure * 2.0 * kRadius * std::sin(kFlatHalfAngle);
}

TEST(BrazilianDisk, FirstFailureAtTheCentreNearTheTensileStrength) {
  // Load control, pressure growing in 120 steps to P = 2.4 MPa pi t R. The elastic stress at
  // the centre of a flattened disc is sigma_x = 0.94 P / (pi t R) (Huang et al. 2015, paper
  // eq. 15 at y = 0), so with ft = 2 MPa (stress onset) the centre fails first at
  // P / (pi t R) = 2.1 MPa; the paper's figure is 2.128 MPa. Required: within 10 % of ft and
  // at the centre: the first damaged elements' mean within 0.15 R of it (sigma_x is within
  // 0.6 % of its centre value there, so mesh noise picks the element). Measured: 2.080 MPa
  // at step 104, one element 2.3 mm (0.09 R) from the centre; on data/'s 18,500-element
  // mesh also 2.080 MPa, 46 elements around a mean 0.08 mm from the centre.
  const auto run =
      test::run_data_scene("brazilian_disk_failure.toml", {"mesh.element_size=1.25e-3"});
  const auto& first = run.result.summary.at("first_damage");
  ASSERT_TRUE(first.is_object()) << "nothing damaged";
  const long step = first.at("step").get<long>();
  const double pressure = 21.7122e6 * static_cast<double>(step) / 120.0;
  const double strength = flat_load(pressure) / (std::numbers::pi * kRadius);
  EXPECT_NEAR(strength, 2e6, 0.1 * 2e6);
  EXPECT_NEAR(strength, 2.128e6, 0.05 * 2.128e6) << "the paper's first-failure strength";
  EXPECT_LT(std::hypot(first.at("x").get<double>(), first.at("y").get<double>()), 0.15 * kRadius);
  // The step before, nothing had damaged: the load at first failure is bracketed to 1 %.
  const auto before =
      test::run_data_scene("brazilian_disk_failure.toml",
                           {"mesh.element_size=1.25e-3", "time.steps=" + std::to_string(step - 1),
                            "load.0.pressure=" + std::to_string(21.7122e6 * (step - 1) / 120.0),
                            "load.1.pressure=" + std::to_string(21.7122e6 * (step - 1) / 120.0)});
  ASSERT_TRUE(before.result.ok) << before.result.reason;
  EXPECT_EQ(before.result.summary.at("damaged_elements").get<long>(), 0);
  // Past the peak a static analysis cannot follow the load: the run says so.
  EXPECT_FALSE(run.result.ok);
  EXPECT_NE(run.result.reason.find("the specimen has failed"), std::string::npos)
      << run.result.reason;
}

TEST(BrazilianDisk, CrackRunsAlongTheLoadedDiameterToBothEnds) {
  // The paper's peak load P = 167.12 kN held (quasi-static steps of 10 us): the first
  // elements damage at the centre, then the crack runs to both flats (paper Fig. 11) within
  // the damage iteration of that step, where the scene ends. Checked on the damaged elements'
  // reference centroids: they reach beyond 0.9 R above and below the centre, 90 % of them lie
  // within 0.3 R of the loaded diameter, and all of those in the middle half (|y| < R / 2)
  // do (measured: 0.97 R, 92 %, 100 %; on the paper's 18,534-element mesh 0.98 R, 91 %,
  // 100 %; the band widens under the flats).
  const auto run = test::run_data_scene("brazilian_disk_crack.toml");
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& first = run.result.summary.at("first_damage");
  ASSERT_TRUE(first.is_object()) << "nothing damaged";
  EXPECT_LT(std::hypot(first.at("x").get<double>(), first.at("y").get<double>()), 0.1 * kRadius);
  const Model& model = run.model;
  int damaged = 0, in_band = 0, middle = 0, middle_in_band = 0;
  double lowest = 0.0, highest = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (model.damage[e] <= 0.0) continue;
    const auto [x, y] = reference_centroid(model, e);
    ++damaged;
    const bool band = std::abs(x) < 0.3 * kRadius;
    in_band += band;
    if (std::abs(y) < 0.5 * kRadius) {
      ++middle;
      middle_in_band += band;
    }
    lowest = std::min(lowest, y);
    highest = std::max(highest, y);
  }
  ASSERT_GT(damaged, 0);
  EXPECT_GT(highest, 0.9 * kRadius);
  EXPECT_LT(lowest, -0.9 * kRadius);
  EXPECT_GE(in_band, 0.9 * damaged) << in_band << " of " << damaged;
  EXPECT_GT(middle, 0);
  EXPECT_EQ(middle_in_band, middle);
  // Exactly the fully broken elements have become blocks of their own (detach_at_damage = 1).
  const auto broken =
      std::count_if(model.damage.begin(), model.damage.end(), [](double w) { return w >= 1.0; });
  EXPECT_GT(broken, 0);
  EXPECT_EQ(run.result.summary.at("detached_elements").get<long>(), broken);
}

/// What the displacement-controlled disk run shows about its split.
struct DiskSplit {
  double peak_strength = 0.0;  // P / (pi R t) at the largest platen force (Pa)
  double final_over_peak = 0.0;
  int damaged = 0;
  double near_diameter = 0.0;         // share of damaged elements within 0.2 R of x = 0
  std::vector<double> large_block_x;  // mean reference x of blocks > 10 % of the elements
  std::vector<std::int32_t> large_block_size;
  double opening_speed = 0.0;  // mean x velocity right of x = 0.2 R less left of -0.2 R (m/s)
  // Largest |work - strain - kinetic - dissipated - snap-back - integrator| / work.
  double energy_gap = 0.0;
  double created = 0.0;     // energy re-solves gained instead of released, over the work
  double integrator = 0.0;  // damped by the time integrator, over the work
  long first_damage_step = 0;
  std::array<double, 2> first_damage_at{};  // summary first_damage x, y (m)
  long inertia_step = 0;  // summary snap_back_inertia: the last quasi-static step, its dt
  double inertia_dt = 0.0;
  // At the split (summary events.first_separation: the first damage pass after which the
  // undamaged elements form two parts of >= 10 % of the area each).
  bool split = false;
  std::vector<double> split_parts;  // the parts' areas, largest first (m^2)
  int split_damaged = 0;
  double split_near_diameter = 0.0;  // share of the damaged elements within 0.2 R of x = 0
  bool split_frame = false;          // its frame was written
};

/// Share of the damaged elements of `model` whose reference centroid lies within 0.2 R of the
/// loaded diameter, and their number.
std::pair<double, int> damage_near_diameter(const Model& model) {
  int damaged = 0, near = 0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (model.damage[e] <= 0.0) continue;
    ++damaged;
    near += std::abs(reference_centroid(model, e)[0]) <= 0.2 * kRadius;
  }
  return {damaged > 0 ? static_cast<double>(near) / damaged : 0.0, damaged};
}

DiskSplit run_displacement_disk(const std::vector<std::string>& overrides,
                                const std::string& scene = "brazilian_disk_displacement.toml") {
  const auto run = test::run_data_scene(scene, overrides, 1);
  EXPECT_TRUE(run.result.ok) << run.result.reason;
  DiskSplit split;
  const auto& force = run.history.at("top.fy");
  double peak = 0.0;
  for (double f : force) peak = std::max(peak, std::abs(f));
  split.peak_strength = peak / (std::numbers::pi * kRadius);
  split.final_over_peak = std::abs(force.back()) / peak;
  const auto& work = run.history.at("energy.external_work");
  for (std::size_t i = 0; i < work.size(); ++i) {
    if (work[i] < 0.01 * work.back()) continue;
    const double gap =
        work[i] - run.history.at("energy.strain")[i] - run.history.at("energy.kinetic")[i] -
        run.history.at("energy.dissipated")[i] - run.history.at("energy.snap_back")[i] -
        run.history.at("energy.integrator")[i];
    split.energy_gap = std::max(split.energy_gap, std::abs(gap) / work[i]);
  }
  split.created =
      run.result.summary.at("energy").at("created_by_resolves").get<double>() / work.back();
  split.integrator = run.history.at("energy.integrator").back() / work.back();
  const auto& summary = run.result.summary;
  if (summary.at("first_damage").is_object()) {
    split.first_damage_step = summary.at("first_damage").at("step").get<long>();
    split.first_damage_at = {summary.at("first_damage").at("x").get<double>(),
                             summary.at("first_damage").at("y").get<double>()};
  }
  if (summary.contains("snap_back_inertia") && summary.at("snap_back_inertia").is_object()) {
    split.inertia_step = summary.at("snap_back_inertia").at("step").get<long>();
    split.inertia_dt = summary.at("snap_back_inertia").at("dt").get<double>();
  }
  if (summary.at("events").contains("first_separation") &&
      run.at_event.contains("first_separation")) {
    const auto& event = summary.at("events").at("first_separation");
    split.split = true;
    split.split_parts = event.at("part_areas").get<std::vector<double>>();
    std::tie(split.split_near_diameter, split.split_damaged) =
        damage_near_diameter(run.at_event.at("first_separation"));
    EXPECT_EQ(event.at("damaged_elements").get<int>(), split.split_damaged);
    split.split_frame = event.at("frame").is_string();
  }
  const Model& model = run.model;
  std::vector<double> x_sum(static_cast<std::size_t>(model.num_blocks), 0.0);
  std::vector<std::int32_t> count(static_cast<std::size_t>(model.num_blocks), 0);
  int near = 0;
  std::vector<double> side_vx[2];
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const auto [x, y] = reference_centroid(model, e);
    x_sum[model.element_block[e]] += x;
    double vx = 0.0;
    for (int corner = 0; corner < 3; ++corner) vx += model.v[2 * model.conn[3 * e + corner]] / 3.0;
    if (std::abs(x) > 0.2 * kRadius) (x > 0.0 ? side_vx[1] : side_vx[0]).push_back(vx);
    ++count[model.element_block[e]];
    if (model.damage[e] <= 0.0) continue;
    ++split.damaged;
    near += std::abs(x) <= 0.2 * kRadius;
  }
  const auto mean = [](const std::vector<double>& v) {
    return v.empty() ? 0.0
                     : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  };
  split.opening_speed = mean(side_vx[1]) - mean(side_vx[0]);
  split.near_diameter = split.damaged > 0 ? static_cast<double>(near) / split.damaged : 0.0;
  for (std::size_t b = 0; b < count.size(); ++b)
    if (count[b] > model.num_elements() / 10) {
      split.large_block_x.push_back(x_sum[b] / count[b]);
      split.large_block_size.push_back(count[b]);
    }
  return split;
}

TEST(BrazilianDisk, DisplacementControlPeaksAtHuangsStrengthAndSplitsInTwo) {
  // Flattened disk (R = 25 mm, 2 alpha = 20 deg, ft = 2 MPa, homogeneous, tension damage),
  // platen at 0.1 mm/s, quasi-static, to a 90 % load drop (data/brazilian_disk_displacement).
  // Peak: Huang et al. (paper eq. 15), P / (pi R t) = ft / (3 cos alpha - 2 alpha / sin alpha)
  // = 2.118 MPa, within 5 %. The crack is judged at the split (issue 26): the first damage
  // pass after which the undamaged elements form two parts of >= 10 % of the area each
  // (summary.json events.first_separation, with its frame events/first_separation.vtu). There
  // the disk is in two halves within 25 % of each other in area. The same at dt / 2 and at
  // h / sqrt(2). Measured (h, dt/2, h/sqrt2): peak 2.157, 2.157, 2.148 MPa (+1.8, +1.8, +1.4 %);
  // halves 949 / 934, 949 / 934, 936 / 849 mm^2; of the damaged elements at the split 77.7 %
  // (of 121), 77.7 % (121) and 45.3 % (360) lie within 0.2 R of the diameter. That share is
  // short of the 80 % issue 26 asks: at h the first damage is at a flat's edge (x = -5.4 mm,
  // y = 23.8 mm; a rigid flat is a rigid punch, its pressure singular at its edges), and
  // damage under the flats grows with the crack within the same held cascade
  // (docs/convergence.md). The disk pressed through cushions meets it (the next test).
  // It is held here at >= 40 %, so that a change that spreads damage further shows (51.5 % at
  // h/sqrt2 before the frames followed turns within a solve).
  // Energy: at every step the work done equals strain + kinetic energy + damage and friction
  // dissipation + the snap-back energy (released as the disk re-settles after each damage
  // event at fixed platens, measured as the fall of the stored energy in that re-solve), to
  // 2 % of the work. Measured: 0.4 %; without the snap-back term 66 % of the work is missing.
  const double alpha = kFlatHalfAngle;
  const double huang = 2e6 / (3.0 * std::cos(alpha) - 2.0 * alpha / std::sin(alpha));
  EXPECT_NEAR(huang, 2.118e6, 0.001e6);
  for (const auto& overrides : std::vector<std::vector<std::string>>{
           {}, {"time.dt=5e-4"}, {"mesh.element_size=8.839e-4"}}) {
    SCOPED_TRACE(overrides.empty() ? std::string("scene as is") : overrides[0]);
    const DiskSplit split = run_displacement_disk(overrides);
    EXPECT_NEAR(split.peak_strength, huang, 0.05 * huang);
    ASSERT_TRUE(split.split) << "the disk never separated";
    EXPECT_TRUE(split.split_frame);
    ASSERT_EQ(split.split_parts.size(), 2u);
    EXPECT_LT(split.split_parts[0] - split.split_parts[1], 0.25 * split.split_parts[0]);
    EXPECT_GE(split.split_near_diameter, 0.40) << split.split_damaged << " damaged";
    EXPECT_LT(split.energy_gap, 0.02);
    // No re-solve gains energy (a sound one only releases it): snap-back is a release, and a
    // negative term would be energy the scheme created hiding in it. Measured: 0 J.
    EXPECT_LT(split.created, 1e-3);
  }
}

TEST(BrazilianDisk, ThroughCushionsFailsAtTheCentreAndSplitsAlongItsDiameter) {
  // The same disk pressed through cushions bonded to its flats (data/brazilian_disk_cushioned:
  // 1 mm thick, E = 2 GPa), which spread the platen's push over the flat as Huang et al.'s
  // strength assumes (a uniform pressure) instead of concentrating it at the flat's edges as
  // the rigid flat above does. Issue 26's criteria, at h, h/sqrt2, h/2 and dt/2:
  // - peak P/(pi R t) within 5 % of ft / (3 cos alpha - 2 alpha / sin alpha) = 2.118 MPa;
  // - at the split (events.first_separation) >= 80 % of the damaged elements within 0.2 R of
  //   the loaded diameter, in two halves within 25 % of each other in area;
  // - the first damage at the centre (within 0.1 R; paper section 3.3), the balance closed at
  //   every step to 2 % of the work, and re-solves creating at most 1 % of it (issue 30).
  // Measured (h, h/sqrt2, h/2, dt/2): peak 2.109, 2.104, 2.104, 2.109 MPa (-0.4 to -0.7 %);
  // within 0.2 R at the split 100 % of 89, 129, 182, 89 damaged elements; first damage 1.3-1.6
  // mm from the centre along the diameter; created by re-solves 5e-5, 1e-5, 0, 0.55 % of the
  // work (at dt/2, in the split step's cascade).
  const double alpha = kFlatHalfAngle;
  const double huang = 2e6 / (3.0 * std::cos(alpha) - 2.0 * alpha / std::sin(alpha));
  for (const auto& overrides : std::vector<std::vector<std::string>>{
           {}, {"mesh.element_size=8.839e-4"}, {"mesh.element_size=6.25e-4"}, {"time.dt=5e-4"}}) {
    SCOPED_TRACE(overrides.empty() ? std::string("scene as is") : overrides[0]);
    const DiskSplit split = run_displacement_disk(overrides, "brazilian_disk_cushioned.toml");
    EXPECT_NEAR(split.peak_strength, huang, 0.05 * huang);
    EXPECT_LT(std::hypot(split.first_damage_at[0], split.first_damage_at[1]), 0.1 * kRadius);
    ASSERT_TRUE(split.split) << "the disk never separated";
    ASSERT_EQ(split.split_parts.size(), 2u);
    EXPECT_LT(split.split_parts[0] - split.split_parts[1], 0.25 * split.split_parts[0]);
    EXPECT_GE(split.split_near_diameter, 0.80) << split.split_damaged << " damaged";
    EXPECT_LT(split.energy_gap, 0.02);
    EXPECT_LT(split.created, 1e-2);
  }
}

TEST(BrazilianDisk, ThroughCushionsRunPastItsSplitCreatesNoEnergyWhereAPartTurns) {
  // Issue 30, the cushioned disk at h/sqrt2 run on to a 90 % load drop: its halves split
  // again and a part by the top flat's edge, joined by damaged elements, turns 0.09 rad in one
  // re-solve. A solve is linear: it moved that part's nodes along the tangents, which
  // stretched its elements by theta^2/2 = 0.43 % both ways, read as strain by the co-rotated
  // measure: 2.33 J created, 56 % of the work. The frames now follow such a turn and Newton
  // steps correct the iterate (summary frame_corrections). Bound: energy created (summary
  // energy_check.created, over the steps and re-solves) at most 1 % of the work (issue 30).
  // Measured: 0.35 % (0.0145 J of 4.146 J), 200 corrections.
  const auto run = test::run_data_scene(
      "brazilian_disk_cushioned.toml",
      {"mesh.element_size=8.839e-4", "time.stop_at_softening=0.9", "output.every=0"}, 1);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& summary = run.result.summary;
  EXPECT_TRUE(summary.at("softening").at("reached").get<bool>());
  EXPECT_GT(summary.at("frame_corrections").get<long>(), 0);
  const auto& check = summary.at("energy_check");
  EXPECT_LT(check.at("created").get<double>(), 0.01 * check.at("scale").get<double>());
  EXPECT_LT(std::abs(summary.at("energy").at("unaccounted").get<double>()),
            0.01 * check.at("scale").get<double>());
}

TEST(BrazilianDisk, SnapBackFollowedWithInertiaSplitsAlongTheDiameter) {
  // fracture.snap_back = "dynamic" (issue 11's "dynamic resolution of a snap-back"): the
  // displacement-controlled disk is loaded quasi-statically; in the step where its damage
  // cascade starts (a re-solve after the first damage event finds more), the run goes on with
  // inertia (Newmark) from that state at a quarter of the shortest wave transit time of an
  // element, h_min / sqrt(E / (rho (1 - nu^2))) / 4 in plane stress, here 5.2e-8 s; it stops
  // at a 95 % load drop. Judged at the split (events.first_separation, as above). Required:
  // the switch no earlier than the first damage, at that dt; the peak within 5 % of Huang's
  // 2.118 MPa; at the split two halves within 25 % of each other in area and >= 80 % of the
  // damaged elements within 0.2 R of the diameter; work = strain + kinetic + dissipated +
  // snap-back + integrator to 2 % at every step, Newmark damping nothing. Measured: first
  // damage in step 222, peak 2.157 MPa (+1.8 %), halves of 831 and 821 mm^2, 91.8 % of 414
  // damaged elements near the diameter at the split (86 % of 536 at the 95 % load drop, when
  // the halves, still held by the flats, have cracked again: docs/method-choices.md, "Damage
  // events").
  const DiskSplit split =
      run_displacement_disk({"fracture.snap_back=dynamic", "time.stop_at_softening=0.95"});
  EXPECT_GE(split.inertia_step, split.first_damage_step);
  EXPECT_NEAR(split.inertia_dt, 5.246e-8, 0.01 * 5.246e-8);
  EXPECT_NEAR(split.peak_strength, 2.118e6, 0.05 * 2.118e6);
  ASSERT_TRUE(split.split) << "the disk never separated";
  ASSERT_EQ(split.split_parts.size(), 2u);
  EXPECT_LT(split.split_parts[0] - split.split_parts[1], 0.25 * split.split_parts[0]);
  EXPECT_GE(split.split_near_diameter, 0.80) << split.split_damaged << " damaged";
  EXPECT_LT(split.energy_gap, 0.02);
  EXPECT_LT(std::abs(split.integrator), 1e-6);
}

TEST(BrazilianDisk, SnapBackWithInertiaThatOnlyTimeEndWouldEndFailsAtOnce) {
  // Once a cascade is followed with inertia every later step is dynamic: the same scene
  // without its softening stop would need (0.5 - 0.222) s / 5.2e-8 s = 5.3e6 steps (hours).
  // Required: the run ends at the switch and says why, naming the keys that end it; the
  // switch step is the last row of history.csv (measured: step 225, three after the first
  // damage: the step cut at the onset, the onset's own step, the cascade's).
  std::istringstream file(test::read_text(test::data_file("brazilian_disk_displacement.toml")));
  std::string scene, line;
  while (std::getline(file, line))
    if (line.find("softening") == std::string::npos) scene += line + "\n";
  const auto run = test::run_scene_text(scene, {"fracture.snap_back=dynamic"}, 1);
  ASSERT_FALSE(run.result.ok);
  const std::string& reason = run.result.reason;
  const std::string cascade = ": a damage cascade is followed with inertia";
  ASSERT_NE(reason.find(cascade), std::string::npos) << reason;
  ASSERT_EQ(reason.rfind("step ", 0), 0u) << reason;
  const long step = std::stol(reason.substr(5, reason.find(cascade) - 5));
  EXPECT_NE(reason.find("time.stop_at_softening"), std::string::npos);
  const long first_damage = run.result.summary.at("first_damage").at("step").get<long>();
  EXPECT_GE(step, first_damage);
  EXPECT_LE(step, first_damage + 3);
  EXPECT_EQ(run.history.at("top.fy").size(), static_cast<std::size_t>(step + 1));
}

/// The platen force and the largest principal stress of the elastic flattened disk
/// (data/verification/halved_disk.geo) pressed by `travel` (m), cut along the loaded diameter
/// by a frictionless joint or not.
struct PressedDisk {
  double force = 0.0;       // |top.fy| (N)
  double largest_s1 = 0.0;  // Pa
  double rim_s1 = 0.0;      // largest s1 within 0.2 R of the horizontal diameter, r > 0.8 R
  double largest_x = 0.0;   // reference centroid of the element with the largest s1 (m)
  int above_strength = 0;   // elements with s1 > 2 MPa
};

PressedDisk press_disk(bool cut, double travel) {
  std::string scene = test::scene_table("halved-disk", "static", "plane = \"stress\"\n") +
                      "[time]\nsteps = 1\n[mesh]\ngeo = \"halved_disk.geo\"\n" +
                      test::material("*", 2600.0, 20e9, 0.2) + test::fixed("bottom_flat", {"y"}) +
                      "[[boundary]]\non = \"top_flat\"\nvelocity_y = " + std::to_string(-travel) +
                      "\n" + test::probe_on("top", "top_flat", {"fy"}) + test::no_frames();
  // Intact: x held at the flats' midpoints, as in data/; cut: each half at its own.
  scene += cut ? test::joint("left", "right", 0.0) + test::fixed("bottom_left", {"x"}) +
                     test::fixed("bottom_right", {"x"})
               : test::fixed("bottom", {"x"}) + test::fixed("top", {"x"});
  const auto run = test::run_scene_text(
      scene, {}, 1,
      {{"halved_disk.geo", test::read_text(test::data_file("verification/halved_disk.geo"))}});
  EXPECT_TRUE(run.result.ok) << run.result.reason;
  PressedDisk disk;
  disk.force = std::abs(run.history.at("top.fy").back());
  const Model& model = run.model;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const double* s = &model.stress[3 * static_cast<std::size_t>(e)];
    const double s1 = 0.5 * (s[0] + s[1]) + std::hypot(0.5 * (s[0] - s[1]), s[2]);
    const auto [x, y] = reference_centroid(model, e);
    if (s1 > disk.largest_s1) {
      disk.largest_s1 = s1;
      disk.largest_x = x;
    }
    if (std::hypot(x, y) > 0.8 * kRadius && std::abs(y) < 0.2 * kRadius)
      disk.rim_s1 = std::max(disk.rim_s1, s1);
    disk.above_strength += s1 > 2e6;
  }
  return disk;
}

TEST(BrazilianDisk, HalvesCutAlongTheDiameterStayOverstressedAtThePeakTravel) {
  // Why the displacement-controlled disk cracks again after its main crack (issue 11 asks
  // for >= 80 % of the damage within 0.2 R together with a > 90 % load drop). At the platen
  // travel of the split step (22.2 um, data/brazilian_disk_displacement.toml), the intact
  // elastic disk peaks at ft at its centre: s1 = 2 MPa within 5 % (Huang et al.'s load, eq.
  // 15), at |x| < 0.1 R. Cut along the loaded diameter (a frictionless joint, the crack made
  // before loading), each half is still pressed between its half-flats, like a column loaded
  // off its centroid: it keeps 70-90 % of the intact force and its largest s1 exceeds 1.5 ft,
  // away from the cut (|x| > 0.2 R), with the rim at mid-height above ft too. So at held
  // platens the halves must crack again before the load can fall by 90 %; a crack along the
  // diameter alone cannot drop it. Measured: 169.6 kN intact, 135.1 kN cut (80 %); s1 2.00
  // MPa at the centre intact, 3.25 MPa (1.6 ft) cut, at (-10.8, 22.3) mm, by the rim beside
  // the top flat; rim at mid-height 2.15 MPa; 218 elements above ft.
  constexpr double kTravel = 22.2e-6, kStrength = 2e6;
  const PressedDisk intact = press_disk(false, kTravel);
  const PressedDisk cut = press_disk(true, kTravel);
  EXPECT_NEAR(intact.largest_s1, kStrength, 0.05 * kStrength);
  EXPECT_LT(std::abs(intact.largest_x), 0.1 * kRadius);
  EXPECT_GT(cut.force, 0.7 * intact.force);
  EXPECT_LT(cut.force, 0.9 * intact.force);
  EXPECT_GT(cut.largest_s1, 1.5 * kStrength);
  EXPECT_GT(std::abs(cut.largest_x), 0.2 * kRadius);
  EXPECT_GT(cut.rim_s1, kStrength);
  EXPECT_GT(cut.above_strength, 100);
}

TEST(BrazilianDisk, DynamicSplitClosesItsEnergyBalance) {
  // The same disk with inertia (issue 11): platen at 0.1 m/s, dt = 0.1 us, to a 95 % load
  // drop. It runs through the split, the halves fly apart faster than the platen moves (the
  // mean x velocity of the rock right of x = 0.2 R less that left of -0.2 R exceeds 0.1 m/s),
  // and at every step past 1 % of
  // the final work, work = strain + kinetic energy + damage and friction dissipation + what
  // the integrator damped, to 2 % of the work. Newmark's average acceleration damps nothing
  // (its term is round-off); DDA's scheme damps m (a_n - a_{n+1}) du / 2 a step, which the
  // balance books (summary energy.integrator_dissipation). Measured (Newmark, DDA): peak
  // 174.4, 175.2 kN (P / (pi R t) 2.22, 2.23 MPa: Huang's 2.118 plus the platen's rate), gap
  // 0.49, 0.52 %; halves opening at 0.41, 0.60 m/s; DDA damped 8.0 % of the work. Re-solves
  // with inertia are not measured as snap-back (the energy they free is kinetic),
  // so summary energy.created_by_resolves is 0 by construction and not checked. Before the overlaps
  // that a detachment exposes were forgiven with inertia too, a copy of a split node found 1.6 um
  // deep in the face across the crack was thrown at 19 m/s, and 3.3 % (Newmark) to 13 % (DDA) was
  // created.
  for (const char* integrator : {"newmark", "dda"}) {
    SCOPED_TRACE(integrator);
    const DiskSplit split = run_displacement_disk(
        {"scene.analysis=dynamic", std::string("time.integrator=") + integrator, "time.dt=1e-7",
         "time.end=4e-4", "boundary.3.velocity_y=-0.1", "time.stop_at_softening=0.95"});
    EXPECT_LT(split.final_over_peak, 0.05);
    EXPECT_NEAR(split.peak_strength, 2.118e6, 0.1 * 2.118e6);
    EXPECT_GT(split.opening_speed, 0.1);
    EXPECT_LT(split.energy_gap, 0.02);
    if (std::string(integrator) == "newmark")
      EXPECT_LT(std::abs(split.integrator), 1e-6);
    else
      EXPECT_GT(split.integrator, 0.01);
  }
}

/// The notched bar's response at one mesh size (data/notched_bar_tension.toml).
struct BarResponse {
  double peak = 0.0;           // largest pull (N)
  double plateau = 0.0;        // mean pull over 5-20 um of travel, after the peak (N)
  double break_opening = 0.0;  // travel (m) where the pull first falls below 5 % of the peak
  double dissipated = 0.0;     // summary energy.damage_dissipation (J)
};

BarResponse run_notched_bar(const std::vector<std::string>& overrides) {
  const auto run = test::run_data_scene("notched_bar_tension.toml", overrides, 1);
  EXPECT_TRUE(run.result.ok) << run.result.reason;
  BarResponse bar;
  const auto& force = run.history.at("right.fx");
  const auto& travel = run.history.at("right.ux");
  const auto top = std::max_element(force.begin(), force.end());
  bar.peak = *top;
  int count = 0;
  for (std::size_t i = static_cast<std::size_t>(top - force.begin()); i < force.size(); ++i) {
    if (bar.break_opening == 0.0 && force[i] < 0.05 * bar.peak) bar.break_opening = travel[i];
    if (travel[i] >= 5e-6 && travel[i] <= 20e-6) {
      bar.plateau += force[i];
      ++count;
    }
  }
  bar.plateau /= std::max(count, 1);
  bar.dissipated = run.result.summary["energy"]["damage_dissipation"].get<double>();
  return bar;
}

TEST(CrackBand, NotchedBarPostPeakDoesNotChangeWithRefinement) {
  // Bazant-Oh crack band (material.fracture_energy): each element's ultimate strain follows
  // from its width h = sqrt(2 A) so that breaking it dissipates G_f per unit crack area
  // (kernels crack_band_ultimate_strain). Homogeneous bar with round notches, 10 mm ligament,
  // G_f = 5 J/m^2, ft = 2 MPa, lambda = 0.1, pulled 0.25 um a step, at h = 0.7, 0.495 and
  // 0.35 mm (data/notched_bar_tension.toml). Closed forms: the crack dissipates
  // G_f x ligament x thickness = 0.05 J, within 15 % (one crack, whose band is one to two
  // elements wide as it zig-zags through the unstructured mesh); it opens by G_f / (lambda ft)
  // = 25 um on the residual plateau before its last element breaks, so the pull falls below
  // 5 % of its peak at 25 um of travel, within 10 %. Refinement: the peak within 1.5 %, the
  // plateau pull within 10 % of the coarsest mesh's.
  // Measured (docs/convergence.md): dissipated 0.0437, 0.0527, 0.0562 J; break at 23.7, 24.7,
  // 25.7 um; peak 12.331, 12.227, 12.193 kN; plateau 2.16, 2.23, 2.34 kN. The peak is the
  // located onset at the notch root (issue 26); the notch's stress concentration grows as the
  // mesh resolves it, so the onset comes 1.1 % sooner at h / 2. (Steps that ran the damage at
  // their end recorded the pull after it: 10.96 kN on every mesh.) Under the load step the
  // peak moves 0.006 % from dt x 2 to dt / 4 (CrackBand.NotchedBarPeakDoesNotMoveWithTheLoadStep).
  // Without fracture_energy (ultimate_strain = 5, the paper's law) the bar breaks within 3 um of
  // travel and dissipates under a quarter of G_f x ligament.
  const double gf = 5.0, ligament = 0.01, opening = gf / (0.1 * 2e6);
  std::vector<BarResponse> bars;
  for (const char* h : {"7e-4", "4.95e-4", "3.5e-4"}) {
    SCOPED_TRACE(std::string("element_size ") + h);
    bars.push_back(run_notched_bar({std::string("mesh.element_size=") + h}));
    const BarResponse& bar = bars.back();
    EXPECT_NEAR(bar.dissipated, gf * ligament, 0.15 * gf * ligament);
    EXPECT_NEAR(bar.break_opening, opening, 0.1 * opening);
    EXPECT_NEAR(bar.peak, bars[0].peak, 0.015 * bars[0].peak);
    EXPECT_NEAR(bar.plateau, bars[0].plateau, 0.1 * bars[0].plateau);
  }

  // The paper's law without the crack band breaks the ligament almost at once: the test
  // above would see it.
  std::string text = test::read_text(test::data_file("notched_bar_tension.toml"));
  const std::string key = "fracture_energy = 5.0";
  ASSERT_NE(text.find(key), std::string::npos);
  text.replace(text.find(key), key.size(), "ultimate_strain = 5.0");
  const auto brittle = test::run_scene_text(
      text, {}, 1,
      {{"notched_bar_tension.geo", test::read_text(test::data_file("notched_bar_tension.geo"))}});
  ASSERT_TRUE(brittle.result.ok) << brittle.result.reason;
  const auto& travel = brittle.history.at("right.ux");
  EXPECT_LT(travel.back(), 0.2 * opening);
  EXPECT_LT(brittle.result.summary["energy"]["damage_dissipation"].get<double>(),
            0.25 * gf * ligament);
}

TEST(CrackBand, NotchedBarPeakDoesNotMoveWithTheLoadStep) {
  // Issue 26: a step that passes an undamaged element's onset is cut at it (to within the
  // damage band and fracture.growth_tolerance), and a history row records the state there;
  // the onset's damage runs in the next step, of no length. The peak is then the physical
  // one whatever the load step: the notched bar's pull at dt x 2, dt, dt / 2 and dt / 4 (0.5,
  // 0.25, 0.125 and 0.0625 um of travel a step) within 1 % of each other (measured 12,331.0,
  // 12,331.4, 12,331.6 and 12,331.7 N: 0.006 %; steps that ran their onsets' damage at their
  // end recorded 10.96 kN, and the stepped-over onset moved it 9.4 % from dt to dt / 4). The
  // row of the peak is the onset's: the first damage comes in the next step, at its time.
  std::vector<double> peaks;
  for (const char* dt : {"1.0", "0.5", "0.25", "0.125"}) {
    SCOPED_TRACE(std::string("time.dt=") + dt);
    const auto run = test::run_data_scene("notched_bar_tension.toml",
                                          {std::string("time.dt=") + dt, "output.every=0"}, 1);
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    const auto& force = run.history.at("right.fx");
    const auto top = std::max_element(force.begin(), force.end());
    peaks.push_back(*top);
    const auto row = static_cast<std::size_t>(top - force.begin());
    const auto& first = run.result.summary.at("events").at("first_damage");
    EXPECT_EQ(first.at("step").get<long>(), std::lround(run.history.at("step")[row]) + 1);
    EXPECT_DOUBLE_EQ(first.at("time").get<double>(), run.history.at("time")[row]);
    EXPECT_GE(run.result.summary.at("located_onsets").get<long>(), 1);
  }
  const auto [low, high] = std::minmax_element(peaks.begin(), peaks.end());
  EXPECT_LT(*high - *low, 0.01 * *low);
}

/// The notched beam in three-point bending (data/notched_beam_bending.toml) at one load step.
struct BeamResponse {
  double peak = 0.0;          // largest pad force (N)
  double near_midspan = 0.0;  // share of damaged elements within 5 mm (2 element sizes) of it
  int damaged = 0;
  bool separated = false;  // events.first_separation: the crack cut the beam in two
};

BeamResponse run_notched_beam(const std::string& dt) {
  const auto run =
      test::run_data_scene("notched_beam_bending.toml", {"time.dt=" + dt, "output.every=0"}, 1);
  EXPECT_TRUE(run.result.ok) << run.result.reason;
  BeamResponse beam;
  const auto& force = run.history.at("pad.fy");
  for (const double f : force) beam.peak = std::max(beam.peak, std::abs(f));
  const Model& model = run.model;
  int near = 0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (model.damage[e] <= 0.0) continue;
    ++beam.damaged;
    near += std::abs(reference_centroid(model, e)[0] - 0.1) <= 5e-3;
  }
  beam.near_midspan = beam.damaged > 0 ? static_cast<double>(near) / beam.damaged : 0.0;
  beam.separated = run.result.summary.at("events").contains("first_separation");
  return beam;
}

TEST(CrackBand, NotchedBarRunOnEndsWhenNothingJoinsItsEnds) {
  // Without its softening stop the bar is pulled on after its crack has run through the
  // ligament. The pulled end (moving in x) and the held end (fixed in x) are then joined by no
  // element with w < 1 and no closed contact, so nothing can carry the pull: the run ends at
  // that step, ok, and says why (summary.json disintegration, cause "no_load_path";
  // engine/damage/load_path), instead of pulling a broken bar to its end time. Measured (29
  // November 2026): ends at step 120 (t = 59.5 s of 120) with 26 blocks, the largest 49.8 % of
  // the bar, the pull 0.41 % and then 0 of its peak.
  Scene scene = read_scene(test::data_file("notched_bar_tension.toml"), {"output.every=0"});
  scene.time.stop_at_softening.reset();
  scene.time.softening_probe.clear();
  test::TempDir dir;
  const test::SceneRun run = test::run_scene(scene, dir.path(), 1);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& summary = run.result.summary;
  ASSERT_TRUE(summary.contains("disintegration"));
  const auto& end = summary["disintegration"];
  EXPECT_EQ(end["cause"].get<std::string>(), "no_load_path");
  EXPECT_EQ(end["step"].get<long>(), summary["steps"].get<long>());
  EXPECT_LT(run.history.at("time").back(), scene.time.end);
  // Two halves are left, each far above a fragment: the fragment count could not end it.
  EXPECT_GT(end["largest_block_share"].get<double>(), 0.3);
  const auto& force = run.history.at("right.fx");
  const double peak = *std::max_element(force.begin(), force.end());
  EXPECT_LT(std::abs(force.back()), 0.01 * peak);
  EXPECT_TRUE(summary["energy_check"]["balance_closes"].get<bool>());
}

TEST(NotchedBeam, PeakDoesNotMoveWithTheLoadStepAndTheCrackRunsFromTheNotch) {
  // Issue 26's standard test that no one tuned: a single-edge-notched beam in three-point
  // bending (200 x 50 mm, span 180 mm, notch 10 mm with a 1 mm round tip, E = 30 GPa,
  // ft = 3 MPa, the paper's law, tension damage only, elastic ends over the supports), pad
  // moved down 0.5 um a step, run to a 95 % load drop. Required: at dt x 2, dt, dt / 2 and
  // dt / 4 the peak pad force within 1 % of each other; >= 80 % of the damaged elements
  // within two element sizes (5 mm) of midspan; the crack cuts the beam in two
  // (events.first_separation). Measured: peaks 1,329.6, 1,329.3, 1,329.3, 1,331.8 N
  // (0.19 %), 60 elements damaged, all within 5 mm of midspan. Run by whole steps
  // (fracture.locate_onsets = false, growth_tolerance = 0) the peak moves with the load step
  // (docs/convergence.md, "Notched beam"). The energy balance closes at every dt (issue 30;
  // checked at dt by AfterTheBreakTheLoadStaysDownAndTheRestraintHoldsNoWork): unaccounted
  // 0.003, 0.001, 0.001 and 0.009 % of the work, the restraint 0.0001-0.025 % (before it
  // relaxed in settling solves: 2.4 and 2.7 % unaccounted at dt / 2 and dt / 4, 8.3-8.9 %
  // held by the restraint).
  std::vector<double> peaks;
  for (const char* dt : {"1e-2", "5e-3", "2.5e-3", "1.25e-3"}) {
    SCOPED_TRACE(std::string("time.dt=") + dt);
    const BeamResponse beam = run_notched_beam(dt);
    peaks.push_back(beam.peak);
    EXPECT_GT(beam.damaged, 0);
    EXPECT_GE(beam.near_midspan, 0.8) << beam.damaged << " damaged";
    EXPECT_TRUE(beam.separated);
  }
  const auto [low, high] = std::minmax_element(peaks.begin(), peaks.end());
  EXPECT_LT(*high - *low, 0.01 * *low);
}

TEST(NotchedBeam, AfterTheBreakTheLoadStaysDownAndTheRestraintHoldsNoWork) {
  // Issue 30: once the ligament under the pad breaks, the half on the roller (free in x) is a
  // mechanism that only the fragment restraint holds. Run 0.4 s (40 um of pad travel, 80
  // steps) past the scene's 95 % load drop: after the break the pad force stays below 5 % of
  // the peak (Required), and the restraint's work plus |unaccounted| is at most 1 % of the
  // external work (the bound). Measured: the force falls from 780 N to 17 N in the
  // breaking step, then 4.0, 1.8, 0.9 N ... (at most 0.3 % of the 1,329 N peak); the
  // restraint holds 6.2e-7 J of 0.058 J (it held 5.1e-3 J, 8.8 %, before it relaxed in
  // settling solves: the half settled against it over three steps), unaccounted 1.4e-6 J.
  Scene scene =
      read_scene(test::data_file("notched_beam_bending.toml"), {"output.every=0", "time.end=1.2"});
  scene.time.stop_at_softening.reset();
  scene.time.softening_probe.clear();
  test::TempDir dir;
  const test::SceneRun run = test::run_scene(scene, dir.path(), 1);
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& force = run.history.at("pad.fy");
  double peak = 0.0;
  std::size_t peak_row = 0;
  for (std::size_t i = 0; i < force.size(); ++i)
    if (std::abs(force[i]) > peak) {
      peak = std::abs(force[i]);
      peak_row = i;
    }
  // The break: the first row after the peak below 5 % of it.
  std::size_t broken = peak_row;
  while (broken < force.size() && std::abs(force[broken]) >= 0.05 * peak) ++broken;
  ASSERT_LT(broken + 50, force.size()) << "no break 50 rows before the end";
  for (std::size_t i = broken; i < force.size(); ++i)
    EXPECT_LT(std::abs(force[i]), 0.05 * peak) << "row " << i;
  const auto& energy = run.result.summary.at("energy");
  const double work = energy.at("external_work").get<double>();
  EXPECT_LE(
      energy.at("anchor_work").get<double>() + std::abs(energy.at("unaccounted").get<double>()),
      0.01 * work);
}

TEST(CrackBand, ElementsTooWideForTheirFractureEnergyAreRefused) {
  // An element wider than 2 E0 G_f / ft0^2 would need eta < 1: it releases more than G_f h
  // at onset alone. G_f = 0.05 J/m^2 puts the limit at 0.5 mm, under the 1 mm mesh: the run is
  // refused before it starts (exit 2), naming the key and the element size that would do.
  Scene scene =
      read_scene(test::data_file("notched_bar_tension.toml"), {"material.0.fracture_energy=0.05"});
  try {
    Simulation sim(scene, build_scene_model(scene));
    FAIL() << "a mesh too coarse for its crack band was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "material[0].fracture_energy");
    EXPECT_NE(std::string(error.what()).find("element_size below"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace rockdd

// The paper's uniaxial compression benchmark (METHOD.md "The paper's benchmarks", 4; paper
// section 3.4, Figs. 14-15): a 150 mm x 75 mm heterogeneous specimen (Weibull m = 1.5 for E,
// ft and c) pressed by a platen at 0.02 mm/s. data/uniaxial_compression.toml has the paper's
// 8,100 elements; these tests run it on 900 (15 x 30 cells), where a run to 70 % softening
// takes about a second.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include "support/data_file.hpp"
#include "support/file_text.hpp"
#include "support/scene_run.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

constexpr double kWidth = 0.075, kHeight = 0.15;  // m (thickness 1 m)

/// The test mesh and any further overrides.
std::vector<std::string> coarse(std::vector<std::string> more = {}) {
  more.insert(more.begin(), "mesh.divisions=[15, 30]");
  return more;
}

/// Axial stress (Pa, compression positive) of each history row.
std::vector<double> axial_stress(const test::SceneRun& run) {
  std::vector<double> stress;
  for (const double fy : run.history.at("top.fy")) stress.push_back(-fy / kWidth);
  return stress;
}

TEST(UniaxialCompression, ElasticSpecimenLiesBetweenTheReussAndVoigtBounds) {
  // Before any damage the heterogeneous specimen is linear: its modulus sigma / eps (smooth
  // platens, uniaxial stress on average) lies between the Reuss bound 1 / <1/E> (uniform
  // stress) and the Voigt bound <E> (uniform strain) of the drawn moduli, area weighted
  // (Hill 1952). Strengths are raised so that nothing damages in the step. Measured: 42.1 GPa,
  // 79 % above Reuss (23.5 GPa) and 17 % below Voigt (50.5 GPa): with m = 1.5 the moduli
  // span more than a factor of ten, and the softest ones pull the harmonic mean down.
  const auto run = test::run_data_scene(
      "uniaxial_compression.toml",
      coarse({"time.end=0.05", "material.0.tensile_strength=1e12", "material.0.cohesion=1e12"}));
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  ASSERT_EQ(run.result.summary.at("damaged_elements").get<long>(), 0);
  const Model& model = run.model;
  double area = 0.0, voigt = 0.0, compliance = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    area += model.area0[e];
    voigt += model.area0[e] * model.young[e];
    compliance += model.area0[e] / model.young[e];
  }
  voigt /= area;
  const double reuss = area / compliance;
  const double modulus = axial_stress(run).back() / (-run.history.at("top.uy").back() / kHeight);
  EXPECT_GT(modulus, reuss) << "Reuss " << reuss << ", Voigt " << voigt;
  EXPECT_LT(modulus, voigt) << "Reuss " << reuss << ", Voigt " << voigt;
}

TEST(UniaxialCompression, StressStrainCurveRisesPeaksAndSoftens) {
  // Weak elements damage from the first steps; the curve bends, peaks and falls once cracks
  // join into a band across the specimen. The run ends once the platen force has fallen 70 %
  // below its peak (time.stop_at_softening). Required: the peak is neither the first nor the
  // last row, the stress rises through a quarter, half and three quarters of the time to
  // the peak, and the last row is at most 30 % of the peak. Measured (seed 1): peak 9.64 MPa
  // at 2.1 s (eps = 2.8e-4), 2.37 MPa at 3.1 s; 8,100 elements: 9.23 MPa at 1.85 s.
  const auto run = test::run_data_scene("uniaxial_compression.toml", coarse());
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const std::vector<double> stress = axial_stress(run);
  const auto peak =
      static_cast<std::size_t>(std::max_element(stress.begin(), stress.end()) - stress.begin());
  ASSERT_GT(peak, 4u);
  ASSERT_LT(peak + 1, stress.size());
  EXPECT_LT(stress[peak / 4], stress[peak / 2]);
  EXPECT_LT(stress[peak / 2], stress[3 * peak / 4]);
  EXPECT_LT(stress[3 * peak / 4], stress[peak]);
  EXPECT_LE(stress.back(), 0.3 * stress[peak]);
  const auto& softening = run.result.summary.at("softening");
  EXPECT_TRUE(softening.at("reached").get<bool>());
  EXPECT_NEAR(softening.at("peak").get<double>(), stress[peak] * kWidth, 1e-9 * stress[peak]);
  // Fracture happened: the fully broken elements became blocks of their own
  // (detach_at_damage = 1), and only they did.
  const Model& model = run.model;
  const auto broken =
      std::count_if(model.damage.begin(), model.damage.end(), [](double w) { return w >= 1.0; });
  EXPECT_GT(broken, 0);
  EXPECT_EQ(run.result.summary.at("detached_elements").get<long>(), broken);
}

TEST(UniaxialCompression, EnergyBalanceHoldsThroughTheCollapse) {
  // Issue 11: work = strain (elements and contact springs) + kinetic + dissipated (damage,
  // friction) + snap-back at every step, to 2 % of the work done so far, through the
  // collapse to 70 % softening. Seeds 2 and 4 collapse through split nodes at the platen and
  // blocks that turn in a step: before the fixes (docs/method-choices.md, "Energy balance",
  // "Large rotations") seed 2 left 2.1 % at its last step on this mesh (the work of a split
  // platen node's copy that had left the constraint), and the paper's mesh 660 %. Measured:
  // at most 0.04 % on seeds 1-4.
  for (const char* seed : {"material.0.seed=2", "material.0.seed=4"}) {
    SCOPED_TRACE(seed);
    const auto run = test::run_data_scene("uniaxial_compression.toml", coarse({seed}));
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    const auto& h = run.history;
    const auto& work = h.at("energy.external_work");
    for (std::size_t i = 1; i < work.size(); ++i) {
      const double gap = work[i] - h.at("energy.strain")[i] - h.at("energy.kinetic")[i] -
                         h.at("energy.dissipated")[i] - h.at("energy.snap_back")[i];
      EXPECT_LE(std::abs(gap), 0.02 * work[i]) << "step " << h.at("step")[i];
    }
    EXPECT_LT(std::abs(run.result.summary.at("energy").at("unaccounted").get<double>()),
              0.02 * work.back());
  }
}

TEST(UniaxialCompression, StrainOnsetRunsToSofteningWithoutCollapsingTheStep) {
  // tension_onset = "strain" (eps_bar >= ft0 / E0, METHOD.md) fires in compression from the
  // lateral strain, long before the stress onset. Issue 11: it once collapsed dt (to 1e-6 s).
  // Required, on the paper's mesh (seed 1): the run reaches 20 % softening with no step
  // redone, in at most the steps of time.dt to that time plus three per located onset (each
  // onset cuts a step at it, runs its damage in a step of no length, and restarts the step
  // growth). A collapsing dt takes thousands. Steps cut at an onset are as short as the onset
  // is close, so the dt column is no measure of collapse. Measured: 731 steps for 103 of
  // time.dt and 355 located onsets, none redone.
  const auto run = test::run_data_scene(
      "uniaxial_compression.toml",
      {"material.0.tension_onset=strain", "time.stop_at_softening=0.2", "output.every=0"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& summary = run.result.summary;
  EXPECT_TRUE(summary.at("softening").at("reached").get<bool>());
  EXPECT_EQ(summary.at("redone_steps").get<long>(), 0);
  const double dt = run.history.at("dt").front();
  const double reached = summary.at("softening").at("time").get<double>();
  EXPECT_LE(summary.at("steps").get<long>(),
            std::lround(reached / dt) + 3 * summary.at("located_onsets").get<long>());
}

TEST(UniaxialCompression, EndsInAtLeastTwoBlocks) {
  // The band of cracks cuts the specimen: besides the one-element fragments, at least two
  // blocks of 2 % of the elements or more remain (paper: "splitting the sample into two main
  // blocks"). Measured (seed 1): 28 %, 14 %, 10 %, 10 %, 5 % and 3 % of the elements.
  const auto run = test::run_data_scene("uniaxial_compression.toml", coarse());
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const Model& model = run.model;
  std::vector<int> size(static_cast<std::size_t>(model.num_blocks), 0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) ++size[model.element_block[e]];
  const auto large = std::count_if(size.begin(), size.end(),
                                   [&](int n) { return n >= 0.02 * model.num_elements(); });
  EXPECT_GE(large, 2);
}

TEST(UniaxialCompression, PaperSpecimenEndsSplitByAFractureIntoFewLargeBlocks) {
  // Issue 11, on the paper's scene (8,100 elements) run to its end (70 % softening), seeds
  // 1-3. Paper section 3.4: the cracks coalesce into one fracture that splits the sample into
  // two main blocks. Required: at most 20 blocks hold more than 1 % of the elements; the crack
  // faces cut the specimen from its outline to its outline, that is two blocks of at least
  // 5 % of the elements each reach the outline (blocks are separated only by crack faces, so
  // the faces between them run from one side to another); and the balance work = strain +
  // kinetic + dissipated + snap-back leaves at most 2 % of the work at every step, with
  // summary unaccounted + anchor_work at most 2 % of it. Measured at growth_tolerance 3e-4
  // (29 November 2026; seeds 1, 2, 3): 2, 2, 3 blocks over 1 % of the elements; the largest
  // two 70.4 / 17.5 %, 78.9 / 10.5 % and 76.4 / 10.4 %; the splitting fracture runs from the
  // top to the right side in seed 1 and from the left side to the bottom in seed 2 (drawn by
  // tools/plot fracture); restraint 0.090, 0.098, 0.120 % of the work; re-solves create
  // 0, 0 and 0.002 %. Each seed ends with two blocks of >= 10 % of the area (through-going,
  // below), seed 3's second at 10.4 %.
  const std::pair<const char*, double> seeds[] = {
      {"material.0.seed=1", 0.05}, {"material.0.seed=2", 0.2}, {"material.0.seed=3", 0.05}};
  for (const auto& [seed, load_left] : seeds) {
    SCOPED_TRACE(seed);
    const auto run = test::run_data_scene("uniaxial_compression.toml", {seed, "output.every=0"});
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    EXPECT_TRUE(run.result.summary.at("softening").at("reached").get<bool>());
    const Model& model = run.model;
    const auto blocks = static_cast<std::size_t>(model.num_blocks);
    std::vector<int> size(blocks, 0);
    std::vector<std::uint8_t> on_outline(blocks, 0);
    const double cell = kWidth / 45.0;  // the scene's cells are 1.67 mm square
    for (std::int32_t e = 0; e < model.num_elements(); ++e) {
      const std::int32_t b = model.element_block[e];
      ++size[b];
      const auto [x, y] = reference_centroid(model, e);
      if (x < cell || x > kWidth - cell || y < cell || y > kHeight - cell) on_outline[b] = 1;
    }
    const auto n = static_cast<double>(model.num_elements());
    const auto large = std::count_if(size.begin(), size.end(), [&](int k) { return k > 0.01 * n; });
    EXPECT_LE(large, 20);
    int main_blocks = 0;
    for (std::size_t b = 0; b < blocks; ++b) main_blocks += size[b] >= 0.05 * n && on_outline[b];
    EXPECT_GE(main_blocks, 2) << "the specimen is not split";
    // Through-going (issue 26): a connected chain of crack faces (the sides of detached
    // elements) separates the specimen into at least two parts of >= 10 % of its area each;
    // the blocks are exactly those parts.
    std::vector<double> block_area(blocks, 0.0);
    double area = 0.0;
    for (std::int32_t e = 0; e < model.num_elements(); ++e) {
      block_area[model.element_block[e]] += model.area0[e];
      area += model.area0[e];
    }
    const auto parts = std::count_if(block_area.begin(), block_area.end(),
                                     [&](double a) { return a >= 0.1 * area; });
    EXPECT_GE(parts, 2) << "not through-going";
    // The damage that cut it: its first pass is summary.json events.first_separation.
    EXPECT_TRUE(run.result.summary.at("events").contains("first_separation"));
    const auto& h = run.history;
    const auto& work = h.at("energy.external_work");
    for (std::size_t i = 1; i < work.size(); ++i) {
      const double gap = work[i] - h.at("energy.strain")[i] - h.at("energy.kinetic")[i] -
                         h.at("energy.dissipated")[i] - h.at("energy.snap_back")[i] -
                         h.at("energy.integrator")[i];
      EXPECT_LE(std::abs(gap), 0.02 * work[i]) << "step " << h.at("step")[i];
    }
    const auto& energy = run.result.summary.at("energy");
    EXPECT_LE(std::abs(energy.at("unaccounted").get<double>()) +
                  std::abs(energy.at("anchor_work").get<double>()),
              0.02 * work.back());
    // Issue 30: the fragment restraint holds at most 0.5 % of the work when steps end
    // (measured 0.090, 0.098, 0.120 % for seeds 1-3 at growth_tolerance 3e-4).
    EXPECT_LE(energy.at("anchor_work").get<double>(), 5e-3 * work.back());
    // No re-solve creates what the balance would hide as negative snap-back: at most 0.5 %
    // of the work (seed 2 created 3.6 % while pieces cut loose kept stale stiffness frames,
    // docs/method-choices.md "Parts cut loose inside a step"). Measured with located onsets:
    // seed 2 0.33 %, all but 0.02 % of it in one re-solve of the last step's cascade, where
    // friction on the crack faces does 0.019 J while the stored energy rises 0.015 J:
    // contacts that create energy (issue 30). Without located onsets the same seed's other
    // path creates 4e-8 of the work.
    EXPECT_LE(energy.at("created_by_resolves").get<double>(), 5e-3 * work.back());
  }
}

TEST(UniaxialCompression, PeakDoesNotMoveWithTheLoadStepOnSeedsOneToThree) {
  // Issue 26, on the paper's scene (8,100 elements): with onsets located, the peak platen
  // force (summary.json softening.peak, run to 20 % softening) at dt x 2 and dt / 2 within
  // 1 % of dt's, seeds 1-3. Measured at growth_tolerance 3e-4 (docs/convergence.md, dt x 2,
  // dt, dt / 2): seed 1 7.384, 7.426, 7.426 MPa; seed 2 7.737, 7.744, 7.745 MPa; seed 3
  // 7.357, 7.357, 7.356 MPa (at most 0.57 %: seed 1 at dt x 2 takes the path it took at the
  // looser 1e-3).
  const std::pair<const char*, double> seeds[] = {
      {"material.0.seed=1", 0.05}, {"material.0.seed=2", 0.2}, {"material.0.seed=3", 0.05}};
  for (const auto& [seed, load_left] : seeds) {
    SCOPED_TRACE(seed);
    std::vector<double> peaks;
    for (const char* dt : {"time.dt=0.00625", "time.dt=0.0125", "time.dt=0.003125"}) {
      const auto run = test::run_data_scene(
          "uniaxial_compression.toml", {seed, dt, "time.stop_at_softening=0.2", "output.every=0"});
      ASSERT_TRUE(run.result.ok) << dt << ": " << run.result.reason;
      peaks.push_back(run.result.summary.at("softening").at("peak").get<double>());
    }
    EXPECT_NEAR(peaks[1], peaks[0], 0.01 * peaks[0]) << "dt x 2";
    EXPECT_NEAR(peaks[2], peaks[0], 0.01 * peaks[0]) << "dt / 2";
  }
}

TEST(UniaxialCompression, RunPastFailureKeepsItsStep) {
  // Issue 30: the paper's specimen without its softening stop, to t = 4.2 s, three times the
  // peak's travel (seed 1: peak 553,990 N at t = 1.389 s). After the peak the fragments'
  // contacts must settle: a step whose open-close iteration does not settle is redone shorter,
  // and its mass term (the quasi-static regulariser) follows the shorter step. With the
  // scene's dt in it whatever the cut, every halving posed the same problem, and seeds 1 and 2
  // failed (steps 1,450 and 961) with dt below dt_min; seed 2 then ran in steps 40x shorter
  // than before its peak until contacts found apart started open. A halved dt grows back
  // after steps that damaged (onsets are located whatever the step's length): held at its
  // worst rejection's dt, seed 2 took 5,517 steps, 2,764 of them in its last 0.3 s at a
  // median dt of 2e-6 s. Parts that a re-solve turned past K's frames were stretched by the
  // solve's linear turn and read as strained (3.3 / 1.2 / 1.4 % of the work created); the frames
  // now follow and Newton steps correct the iterate (Simulation::follow_turned_frames).
  // Measured (29 November 2026, growth_tolerance 3e-4, the factor updates' break-even of
  // 0.45 sqrt(n) + 4000 / sqrt(max(n, 5000)) columns), seeds 1 / 2 / 3: 1,027 / 1,042 / 1,722
  // steps; median dt after the peak 1.0 / 1.0 / 5.3x below the one before (bound 10x); restraint
  // work 0.09 / 0.11 / 0.15 % of the work (bound 0.5 %); the load's mean over the last half of the
  // travel after the peak 6.6 / 4.9 / 0.3 % of the peak (bound 10 %; at 1e-3 it was 4.6 / 3.6
  // / 3.1 %); created 0.04 / 0.15 / 0.09 %, no step over the energy tolerance (at 1e-3: 0.79 /
  // 0.73 / 0.58 % and 3 / 3 / 1 steps). The paths after the peak follow the round-off: with
  // the break-even at 0.5 sqrt(n), seeds 2 and 3 took 1,024 and 1,616 steps.
  // Still above issue 30's bounds, not tested here: 11.9 / 16.5 / 20.7 open-close
  // iterations a step (12.2 / 23.5 / 14.4 at 1e-3; bound 5) (docs/method-choices.md, "A redone
  // step's mass term", "Frames that follow a turn", "Located onsets" and "The growth tolerance's
  // default").
  const std::pair<const char*, double> seeds[] = {
      {"material.0.seed=1", 0.1}, {"material.0.seed=2", 0.1}, {"material.0.seed=3", 0.1}};
  for (const auto& [seed, load_left] : seeds) {
    SCOPED_TRACE(seed);
    test::TempDir dir;
    Scene scene = read_scene(test::data_file("uniaxial_compression.toml"),
                             {"time.end=4.2", "output.every=0", seed});
    scene.time.stop_at_softening.reset();
    const auto run = test::run_scene(scene, dir.path(), 1);
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    const auto& force = run.history.at("top.fy");
    const auto& dt = run.history.at("dt");
    EXPECT_NEAR(run.history.at("time").back(), 4.2, 1e-9);
    std::size_t peak = 0;
    for (std::size_t i = 0; i < force.size(); ++i)
      if (std::abs(force[i]) > std::abs(force[peak])) peak = i;
    // Steps of no length (an onset's damage) are not steps of the load.
    auto median_dt = [&](std::size_t from, std::size_t to) {
      std::vector<double> steps;
      for (std::size_t i = std::max<std::size_t>(from, 1); i < to; ++i)
        if (dt[i] > 0.0) steps.push_back(dt[i]);
      std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
      return steps[steps.size() / 2];
    };
    EXPECT_LT(median_dt(0, peak), 10.0 * median_dt(peak, dt.size()));
    // Past failure the load is a residual that rises and falls as blocks lock and slip (seed
    // 2 at growth_tolerance 3e-4: 2.8 to 8.3 % of its peak over its last second), so one row
    // says little: the bound is on its mean over the last half of the travel after the peak.
    const auto& time = run.history.at("time");
    const double from = 0.5 * (time[peak] + time.back());
    double impulse = 0.0, span = 0.0;
    for (std::size_t i = peak + 1; i < force.size(); ++i)
      if (time[i] > from) {
        impulse += std::abs(force[i]) * (time[i] - time[i - 1]);
        span += time[i] - time[i - 1];
      }
    ASSERT_GT(span, 0.0);
    EXPECT_LT(impulse / span, load_left * std::abs(force[peak]));
    const auto& energy = run.result.summary["energy"];
    EXPECT_LT(energy["anchor_work"].get<double>(),
              0.005 * energy["external_work"].get<double>());
  }
}

TEST(UniaxialCompression, HomogeneousSpecimenRunPastItsPeakReachesItsEndOrSaysItFellApart) {
  // Issue 30: data/verification/ucs_confined.toml, 1,600 elements confined by p = 20 MPa, run
  // on to twice the peak's travel without a softening stop. Mohr-Coulomb with three principal
  // stresses (METHOD.md): damage starts everywhere when
  // sigma_1 = fc0 + sigma_3 (1 + sin phi) / (1 - sin phi), fc0 = 2 c cos phi / (1 - sin phi).
  const double c = 100e6, phi = 20.0 * std::numbers::pi / 180.0, p = 20e6, width = 0.075;
  const double fc0 = 2.0 * c * std::cos(phi) / (1.0 - std::sin(phi));
  const double confined = fc0 + p * (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
  auto peak_stress = [&](const test::SceneRun& run) {
    double peak = 0.0;
    for (const double f : run.history.at("top.fy")) peak = std::max(peak, -f / width);
    return peak;
  };
  {
    // Plane strain: sigma_3 = p (sigma_z = nu (sigma_x + sigma_y) is larger). The damaged
    // specimen keeps its residual stiffness and carries load to the end. Measured: peak
    // 326.56 MPa (closed form 326.40), 282 steps of the 280 planned, balance closed.
    const auto run = test::run_data_scene("verification/ucs_confined.toml", {"output.every=0"});
    ASSERT_TRUE(run.result.ok) << run.result.reason;
    EXPECT_NEAR(peak_stress(run), confined, 0.005 * confined);
    EXPECT_NEAR(run.history.at("time").back(), 14.0, 1e-9);
    EXPECT_LT(run.result.summary["steps"].get<long>(), 2 * 280);
    EXPECT_FALSE(run.result.summary.contains("disintegration"));
    EXPECT_TRUE(run.result.summary["energy_check"]["balance_closes"].get<bool>());
  }
  {
    // Plane stress, the scene issue 30 ran: the out-of-plane stress (0) is the minor one, so
    // the peak is fc0. Every element damages in one cascade and breaks within the steps
    // after; the pressure then pushes loose triangles that only the restraint holds. It used
    // to go on at dt ~ 2e-5 s (82,000 steps in 10 minutes, t = 8.7 s of 14); it now ends at
    // the step that broke it, and says so. Measured (29 November 2026): peak 285.77 MPa (fc0
    // 285.60), ended at step 132 (t = 6.500 s) with 1,571 blocks, the largest 0.63 % of the
    // specimen.
    // At fracture.growth_tolerance = 3e-4, a scene that rule was not chosen on, one block of
    // 61 elements (3.8 %) stays at w = 0.92-0.98, hanging from the top platen with nothing
    // below it: no chain of rock and closed contacts joins the platens, and the run ends on
    // that instead (step 129, t = 6.373 s); before, it crawled on at dt = 1.2e-5 s past the
    // test's 10 minutes.
    for (const auto& [tolerance, cause] :
         {std::pair{"fracture.growth_tolerance=1e-3", "fragments"},
          std::pair{"fracture.growth_tolerance=3e-4", "no_load_path"}}) {
      SCOPED_TRACE(tolerance);
      const auto run =
          test::run_data_scene("verification/ucs_confined.toml",
                               {"output.every=0", "scene.plane=\"stress\"", tolerance});
      ASSERT_TRUE(run.result.ok) << run.result.reason;
      EXPECT_NEAR(peak_stress(run), fc0, 0.005 * fc0);
      const auto& summary = run.result.summary;
      ASSERT_TRUE(summary.contains("disintegration"));
      const auto& end = summary["disintegration"];
      EXPECT_EQ(end["cause"].get<std::string>(), cause);
      EXPECT_EQ(end["step"].get<long>(), summary["steps"].get<long>());
      EXPECT_LT(end["step"].get<long>(), 200);
      EXPECT_NEAR(end["time"].get<double>(), run.history.at("time").back(), 1e-12);
      EXPECT_GT(end["blocks"].get<int>(), 100);
      if (std::string(cause) == "fragments") {
        EXPECT_LT(end["largest_block_share"].get<double>(), 0.01);
      } else {
        // What is left is a block, not fragments: the rule that counts them could not end it.
        EXPECT_GT(end["largest_block_share"].get<double>(), 0.01);
      }
      // Its balance is open (the restraint holds the last step's loose pieces), and says why.
      const std::string warning = summary["energy_check"].value("warning", "");
      EXPECT_NE(
          warning.find(std::string(cause) == "fragments" ? "loose fragments" : "no chain of rock"),
          std::string::npos)
          << warning;
    }
  }
}

TEST(UniaxialCompression, SeedsGiveDifferentPeaks) {
  // Another seed draws another specimen, hence another peak. Measured: 9.64 and 10.52 MPa.
  const auto a = test::run_data_scene("uniaxial_compression.toml", coarse());
  const auto b = test::run_data_scene("uniaxial_compression.toml", coarse({"material.0.seed=2"}));
  ASSERT_TRUE(a.result.ok) << a.result.reason;
  ASSERT_TRUE(b.result.ok) << b.result.reason;
  const double peak_a = a.result.summary.at("softening").at("peak").get<double>();
  const double peak_b = b.result.summary.at("softening").at("peak").get<double>();
  EXPECT_GT(std::abs(peak_a - peak_b), 1e-3 * peak_a) << peak_a << " vs " << peak_b;
}

TEST(UniaxialCompression, SameSeedSameHistoryWhateverTheThreads) {
  // Draws are keyed by (seed, element, parameter) and every reduction has a fixed order:
  // history.csv is the same file, bit for bit, on 1 and 2 threads, through cracking and
  // sliding.
  test::TempDir one, two;
  const Scene scene = read_scene(test::data_file("uniaxial_compression.toml"), coarse());
  const auto a = test::run_scene(scene, one.path(), 1);
  const auto b = test::run_scene(scene, two.path(), 2);
  ASSERT_TRUE(a.result.ok) << a.result.reason;
  ASSERT_GT(a.result.summary.at("damaged_elements").get<long>(), 0);
  EXPECT_EQ(test::read_text(one.path() / "out" / scene.name / "history.csv"),
            test::read_text(two.path() / "out" / scene.name / "history.csv"));
}

}  // namespace
}  // namespace rockdd

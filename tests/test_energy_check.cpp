// The energy balance as the step control checks it (issue 30): what a step creates, when a
// step is redone for it, the quasi-static scheme's own loss, and the end-of-run warning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "engine/time/energy_check.hpp"
#include "support/command_line.hpp"
#include "support/data_file.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

/// A balance with `work` J done and `strain` J stored, nothing else.
EnergyBalance balance(double work, double strain) {
  EnergyBalance e;
  e.external_work = work;
  e.strain = strain;
  return e;
}

TEST(EnergyCheck, CreatedIsHowFarTheRemainderFellPlusWhatReSolvesGained) {
  // unaccounted = initial + work - kinetic - strain - losses: 10 - 9 = 1 before, 12 - 11.5 =
  // 0.5 after, so the step created 0.5 J; a re-solve that gained 0.25 J adds it.
  EXPECT_DOUBLE_EQ(EnergyCheck::created(balance(10, 9), balance(12, 11.5), 0.0), 0.5);
  EXPECT_DOUBLE_EQ(EnergyCheck::created(balance(10, 9), balance(12, 11.5), 0.25), 0.75);
  // A remainder that grew is a loss, not a creation.
  EXPECT_DOUBLE_EQ(EnergyCheck::created(balance(10, 9), balance(12, 10), 0.0), 0.0);
  // A fall within 1e-9 of the energies involved is round-off.
  EXPECT_DOUBLE_EQ(EnergyCheck::created(balance(100, 99), balance(100, 99 + 1e-8), 0.0), 0.0);
}

TEST(EnergyCheck, ScaleIsTheLargerOfTheWorkAndTheInitialEnergy) {
  EnergyBalance spinning = balance(0.0, 0.0);
  spinning.initial = 175.0;
  EXPECT_DOUBLE_EQ(EnergyCheck::scale(spinning), 175.0);
  EXPECT_DOUBLE_EQ(EnergyCheck::scale(balance(-40.0, 0.0)), 40.0);
}

TEST(EnergyCheck, RedoesWhileHalvingHelpsThenLetsTheStepStand) {
  // Tolerance 1e-3 of a 100 J scale: 0.1 J. An attempt creating 1 J is redone; halved it
  // creates 0.6 J (fell by 40 %, the length is the cause): redone again; then 0.55 J (fell by
  // 8 %, less than the quarter an error of the length loses): it stands, counted.
  EnergyCheck check(1e-3);
  const EnergyBalance after = balance(100.0, 50.0);
  std::string why;
  check.begin_step();
  EXPECT_EQ(check.judge(7, 0.05, after, true, why), EnergyCheck::Verdict::stands);
  EXPECT_EQ(check.judge(7, 1.0, after, true, why), EnergyCheck::Verdict::redo);
  EXPECT_NE(why.find("created 1 J"), std::string::npos) << why;
  EXPECT_NE(why.find("time.energy_tolerance = 0.001"), std::string::npos) << why;
  EXPECT_EQ(check.judge(7, 0.6, after, true, why), EnergyCheck::Verdict::redo);
  EXPECT_EQ(check.judge(7, 0.55, after, true, why), EnergyCheck::Verdict::unresolved);
  EXPECT_EQ(check.rejected(), 2);
  EXPECT_EQ(check.unresolved(), 1);
  EXPECT_EQ(check.worst_unresolved_step(), 7);
  EXPECT_DOUBLE_EQ(check.worst_unresolved_share(), 0.0055);
  // A new step is judged on its own; a step of no length cannot be redone.
  check.begin_step();
  EXPECT_EQ(check.judge(8, 0.55, after, true, why), EnergyCheck::Verdict::redo);
  check.begin_step();
  EXPECT_EQ(check.judge(9, 0.55, after, false, why), EnergyCheck::Verdict::unresolved);
  EXPECT_EQ(check.unresolved(), 2);
}

TEST(EnergyCheck, WarningNamesWhatStaysOpen) {
  EnergyCheck quiet(1e-3);
  EnergyBalance closed = balance(100.0, 99.5);
  EXPECT_EQ(energy_balance_warning(closed, kEnergyBalanceShare, quiet), "");
  EnergyBalance open = balance(100.0, 90.0);
  open.anchor = 2.0;
  const std::string words = energy_balance_warning(open, kEnergyBalanceShare, quiet);
  EXPECT_NE(words.find("8 J unaccounted (8 %)"), std::string::npos) << words;
  EXPECT_NE(words.find("2 J held by the fragment restraint (2 %)"), std::string::npos) << words;
}

/// A 0.1 x 0.1 m plate, 10 GPa, fixed at its bottom, pressed on its top by 1 MPa held from
/// t = 0 (quasi-static: loads do not ramp), dt = 10 s so that the mass term barely slows it.
std::string plate_under_held_load() {
  return test::scene_table("held-load", "quasi-static", "plane = \"strain\"\n") +
         "[time]\ndt = 10.0\nsteps = 6\n" + test::rectangle_mesh(0.1, 0.1, {4, 4}) +
         test::material("", 2600.0, 10e9, 0.25) + test::fixed("bottom") +
         "[[load]]\non = \"top\"\npressure = 1e6\n" + test::probe_on("top", "top", {"uy"}) +
         test::no_frames();
}

TEST(QuasiStaticLoss, LoadAppliedAtOnceLosesWhatTheBodyDoesNotStore) {
  // A load F held on a linear body from rest does work F u on its way to u = K^-1 F and the
  // body stores F u / 2 (Clapeyron): without inertia the other half is the scheme's loss
  // (each step starts at rest), energy.quasi_static_loss = W / 2 to 1e-6 once settled, and
  // nothing is left unaccounted but the co-rotated strain's departure from linearity, which
  // scales with the load: measured 6.0e-7, 6.0e-8, 6.0e-9 of the work at 1, 0.1, 0.01 MPa;
  // 2e-6 allowed. Kinetic energy is 0: no motion is held.
  const auto run = test::run_scene_text(plate_under_held_load());
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& e = run.result.summary["energy"];
  const double work = e["external_work"].get<double>();
  ASSERT_GT(work, 0.0);
  EXPECT_NEAR(e["strain"].get<double>(), 0.5 * work, 1e-6 * work);
  EXPECT_NEAR(e["quasi_static_loss"].get<double>(), 0.5 * work, 1e-6 * work);
  EXPECT_LT(std::abs(e["unaccounted"].get<double>()), 2e-6 * work);
  EXPECT_EQ(e["kinetic"].get<double>(), 0.0);
  EXPECT_TRUE(run.result.summary["energy_check"]["balance_closes"].get<bool>());
  // history.csv carries the balance per row, the remainder included.
  const auto& unaccounted = run.history.at("energy.unaccounted");
  ASSERT_EQ(unaccounted.size(), 7u);
  for (const double u : unaccounted) EXPECT_LT(std::abs(u), 2e-6 * work);
}

TEST(QuasiStaticLoss, TheLoadHeldDiskClosesItsBalance) {
  // data/brazilian_disk_crack.toml: the paper's disk under its peak load, held (issue 30 found
  // 46 % of the work unaccounted at the paper's mesh). The load applied at once loses what the
  // disk does not store, the crack's snap-back the rest: the balance closes to 1 %.
  const auto run = test::run_data_scene("brazilian_disk_crack.toml", {"output.every=0"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& e = run.result.summary["energy"];
  const double work = e["external_work"].get<double>();
  EXPECT_LT(std::abs(e["unaccounted"].get<double>()), 0.01 * work);
  EXPECT_GT(e["quasi_static_loss"].get<double>(), 0.2 * work);
  EXPECT_GT(run.result.summary["damaged_elements"].get<int>(), 50);  // it cracked (92)
}

TEST(EnergyCheck, FrictionalInclineAtTenMillisecondsCreatesLessThanOnePercentAStep) {
  // data/verification/frictional_incline.toml (dynamic, DDA, dt = 10 ms): the block slides
  // s = 1/2 g (sin 30 - tan 15 cos 30) t^2 = 1.340 m in 1 s. Its release once created 2.2 % of
  // the work in one step; booked as DDA's scheme moves it (its end forces' work, exactly:
  // contact_end_point_loss) no step creates more than 0.1 % of the work done by its end even
  // with the check off (time.energy_tolerance = 1; measured 0.043 %, none redone), and the
  // slide is within 1 % of the closed form (measured +0.54 %).
  const auto run = test::run_data_scene("verification/frictional_incline.toml",
                                        {"output.every=0", "time.energy_tolerance=1"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& check = run.result.summary["energy_check"];
  EXPECT_LE(check["largest_step_created_share"].get<double>(), 1e-3 * (1 + 1e-9));
  EXPECT_EQ(check["unresolved_steps"].get<long>(), 0);
  // Every row: what the balance's remainder fell by since the row before is at most 1 % of the
  // work done by then.
  const auto& h = run.history;
  const auto& unaccounted = h.at("energy.unaccounted");
  const auto& work = h.at("energy.external_work");
  for (std::size_t i = 1; i < unaccounted.size(); ++i)
    EXPECT_LE(unaccounted[i - 1] - unaccounted[i], 0.01 * work[i]) << "row " << i;
  const double th = std::numbers::pi / 6, phi = std::numbers::pi / 12, g = 10.0;
  const double t = h.at("time").back();
  const double s = 0.5 * g * (std::sin(th) - std::tan(phi) * std::cos(th)) * t * t;
  const double along =
      h.at("block2.ux").back() * std::cos(th) - h.at("block2.uy").back() * std::sin(th);
  EXPECT_NEAR(along, s, 0.01 * s);
}

TEST(EnergyCheck, RunWhoseStepCannotBeCutFarEnoughFailsNamingTheStepAndTheEnergy) {
  // The toppling block (DDA) held to time.energy_tolerance = 1e-6 with dt_min = dt = 1 ms:
  // step 934, as it lands, creates 0.005 J, 1.04e-6 of the 4.8 kJ scale (measured), and may
  // not be cut, so the run fails (exit 1) and says which step and how much energy, never an
  // `ok` over a created joule. (Newmark's average acceleration, whose trapezoid made a spring
  // that opened within a step give back more than it held, served here until its contact
  // forces became energy-consistent: its fifth step created 0.35 % of the work.)
  test::TempDir dir;
  const auto r = test::rockdd_cli(
      "run " + test::data_file("toppling_block.toml").string() +
          " --set time.energy_tolerance=1e-6 --set time.dt_min=1e-3 --set output.every=0 "
          "--out out",
      dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("step "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("J of energy"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("dt_min"), std::string::npos) << r.output;
}

TEST(EnergyCheck, ToleranceOutOfRangeIsRefused) {
  test::TempDir dir;
  const auto r =
      test::rockdd_cli("run " + test::data_file("verification/frictional_incline.toml").string() +
                           " --set time.energy_tolerance=0 --out out",
                       dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("energy_tolerance"), std::string::npos) << r.output;
}

TEST(TopplingBlock, TallTopplesLandsOnItsSideAndIsNotThrownBack) {
  // data/toppling_block.toml: b / h = 0.25 < tan 20 deg = 0.364, so the block turns about its
  // downhill corner and lands on its long side, a quarter turn (rotation -pi/2 to 0.01 rad),
  // and the joint's friction (40 deg) holds it there. The landing is the step of the most
  // kinetic energy (15.6 kJ); after it the block must not be thrown (the engine of 26 November
  // threw it back up the slope with 2,565 J from 8.9 J):
  //  - no step creates more than time.energy_tolerance = 0.1 % of the work (measured 0.00 %;
  //    it was 1.8 % in a step however short, before DDA's contact work was booked as its
  //    scheme moves it and a contact that slid back past its anchor stuck there);
  //  - the elastic rebound of its far end rocks it back about its downhill corner by at most
  //    0.1 rad (measured 0.057 rad; 0.054 and 0.023 rad at dt / 2 and dt / 4), which moves its
  //    centre up the slope by at most 2 cm (measured 1.1 cm), and no later kinetic energy
  //    reaches a tenth of the landing's (measured 771 J);
  //  - it comes to rest downhill of where it landed (measured 12.8 mm), its centre still to
  //    0.1 mm over the last 0.2 s.
  const auto run = test::run_data_scene("toppling_block.toml", {"output.every=0"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& h = run.history;
  const auto& rotation = h.at("block.rotation");
  const auto& kinetic = h.at("energy.kinetic");
  const auto& time = h.at("time");
  EXPECT_NEAR(rotation.back(), -std::numbers::pi / 2, 0.01);
  const std::size_t landing =
      static_cast<std::size_t>(std::max_element(kinetic.begin(), kinetic.end()) - kinetic.begin());
  ASSERT_GT(landing, 0u);
  ASSERT_LT(landing + 1, kinetic.size());
  const double peak = kinetic[landing];
  // Down the slope is (cos 20, -sin 20): the block's mean displacement along it.
  const double slope = 20.0 * std::numbers::pi / 180.0;
  auto downhill = [&](std::size_t i) {
    return h.at("block.ux")[i] * std::cos(slope) - h.at("block.uy")[i] * std::sin(slope);
  };
  // The first rows after the landing still carry its kinetic energy down: the bound is on
  // what comes back after the impact's 10 ms.
  for (std::size_t i = landing; i < kinetic.size(); ++i) {
    EXPECT_GE(downhill(i), downhill(landing) - 0.02) << "row " << i;
    EXPECT_LE(rotation[i], -std::numbers::pi / 2 + 0.1) << "row " << i;
    if (time[i] > time[landing] + 0.01) {
      EXPECT_LT(kinetic[i], 0.1 * peak) << "row " << i;
    }
  }
  EXPECT_GT(downhill(kinetic.size() - 1), downhill(landing));
  std::size_t settled = kinetic.size() - 1;
  while (settled > 0 && time[settled] > time.back() - 0.2) --settled;
  EXPECT_LT(std::abs(downhill(kinetic.size() - 1) - downhill(settled)), 1e-4);
  EXPECT_LE(run.result.summary["energy_check"]["largest_step_created_share"].get<double>(),
            1e-3 * (1 + 1e-9));
  EXPECT_TRUE(run.result.summary["energy_check"]["balance_closes"].get<bool>())
      << run.result.summary["energy_check"].dump();
}

TEST(TopplingBlock, SquatStands) {
  // The same block 1.0 m wide (data/toppling_block_squat.geo): b / h = 0.625 > tan 20 deg, its
  // centre of mass uphill of its downhill corner, so it stands: at 2 s turned by less than
  // 1e-3 rad and moved less than 0.1 mm (measured 9e-6 rad, 6 um), its balance closed.
  const auto run = test::run_data_scene("toppling_block.toml",
                                        {"output.every=0", "mesh.geo=toppling_block_squat.geo"});
  ASSERT_TRUE(run.result.ok) << run.result.reason;
  const auto& h = run.history;
  EXPECT_LT(std::abs(h.at("block.rotation").back()), 1e-3);
  EXPECT_LT(std::abs(h.at("block.ux").back()), 1e-4);
  EXPECT_LT(std::abs(h.at("block.uy").back()), 1e-4);
  EXPECT_TRUE(run.result.summary["energy_check"]["balance_closes"].get<bool>())
      << run.result.summary["energy_check"].dump();
}

}  // namespace
}  // namespace rockdd

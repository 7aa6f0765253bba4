// The committed state a step attempt starts from (engine/state/committed_state): a rejected
// attempt leaves nothing behind that the next attempt reads.
#include <gtest/gtest.h>

#include <vector>

#include "engine/report/run_result.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

// A square pressed from above: its first step of 1 mm exceeds time.max_step_displacement
// (0.6 mm), so the step is rejected and redone at dt / 2, and dt grows back later and is cut
// again: several redone steps, each after a trial that stressed the block further than the
// committed state.
const std::string kPressedSquare =
    test::scene_table("pressed-square", "quasi-static") +
    "[time]\ndt = 1.0\nend = 4.0\nmax_step_displacement = 6e-4\n" +
    test::rectangle_mesh(1.0, 1.0, {4, 4}) + test::material("body", 2000.0, 1e9, 0.2) +
    test::fixed("bottom", {"y"}) + test::fixed("bottom_left", {"x"}) +
    "[[boundary]]\non = \"top\"\nvelocity_y = -1e-3\n";

TEST(CommittedState, ARedoneAttemptStartsFromTheCommittedStress) {
  // Required: as an attempt starts, the element stress (and strain) it reads, e.g. for the
  // contact force tolerance, is the committed state's, bitwise, also after a rejected trial.
  test::TempDir dir;
  const Scene scene = test::scene_from_text(kPressedSquare, dir.path());
  Simulation sim(scene, build_scene_model(scene));
  std::vector<double> committed_stress, committed_strain;  // as the step's first attempt saw
  int redone = 0, mismatched = 0;
  RunOptions options;
  options.write_outputs = false;
  options.threads = 1;
  options.on_attempt = [&](const AttemptReport& attempt, const Model& model) {
    if (attempt.retries == 0) {
      committed_stress = model.stress;
      committed_strain = model.strain;
      return;
    }
    ++redone;
    if (model.stress != committed_stress || model.strain != committed_strain) ++mismatched;
  };
  const RunResult result = sim.run(options);
  ASSERT_TRUE(result.ok) << result.reason;
  EXPECT_GE(redone, 1) << "the scene must redo a step to test anything";
  EXPECT_EQ(mismatched, 0) << "of " << redone << " redone attempts";
}

}  // namespace
}  // namespace rockdd

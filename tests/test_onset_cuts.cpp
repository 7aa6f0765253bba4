// The lengths a step that passed an onset is cut to (engine/time/onset_cuts). The largest onset
// ratio at an attempt's end is affine in the attempt's length dt where the response is linear:
// r(dt) = r0 + s dt, r0 the part that does not scale with the step (the settling of the
// imbalance the step starts with). The line through two attempts gives r0 and s exactly.
#include "engine/time/onset_cuts.hpp"

#include <gtest/gtest.h>

namespace rockdd {
namespace {

constexpr double kTarget = 1.01;

TEST(OnsetCuts, FirstCutTakesTheStraightPathsFraction) {
  OnsetCuts cuts(kTarget, true);
  EXPECT_DOUBLE_EQ(cuts.next(0.01, 0.3, 1.5, false), 0.003);
  EXPECT_TRUE(cuts.may_cut());
  EXPECT_FALSE(cuts.locates_at_no_length());
}

TEST(OnsetCuts, FirstSolvesWhoseSettlingPassesTheOnsetGiveAStepOfNoLengthThatLocates) {
  // UCS seed 1 before this rule (step 367): r = 2.8688 at dt = 6.25 ms and 2.8569 at 1.07 ms,
  // straight-path fraction 0.17 every time; eight cuts crept down to dt = 5e-9 s with r still
  // 2.854. The line's value at no length, 2.8569 - 2.30 * 0.00107 = 2.854 >= 1.01: no length.
  OnsetCuts cuts(kTarget, true);
  const double first = cuts.next(0.00625, 0.1714, 2.8688, false);
  EXPECT_DOUBLE_EQ(first, 0.1714 * 0.00625);
  EXPECT_EQ(cuts.next(first, 0.1724, 2.8569, false), 0.0);
  EXPECT_TRUE(cuts.locates_at_no_length());
  EXPECT_FALSE(cuts.may_cut());
}

TEST(OnsetCuts, FirstSolvesWhoseLineReachesTheTargetKeepTheStraightPath) {
  // r = 1.0 + 10 dt: the load passes the onset, not the settling; the straight paths stay.
  OnsetCuts cuts(kTarget, true);
  const double first = cuts.next(0.01, 0.5, 1.1, false);
  EXPECT_DOUBLE_EQ(cuts.next(first, 0.4, 1.05, false), 0.4 * first);
  EXPECT_FALSE(cuts.locates_at_no_length());
  EXPECT_TRUE(cuts.may_cut());
}

TEST(OnsetCuts, AStepThatMayNotStandIsCutAlongTheStraightPath) {
  // The last step had no length and located nothing: this one may not have none either.
  OnsetCuts cuts(kTarget, false);
  const double first = cuts.next(0.00625, 0.1714, 2.8688, false);
  EXPECT_DOUBLE_EQ(cuts.next(first, 0.1724, 2.8569, false), 0.1724 * first);
  EXPECT_FALSE(cuts.locates_at_no_length());
}

TEST(OnsetCuts, SettledAttemptsTakeTheRootOfTheirLine) {
  // r = 1.002 + 4 dt after the growth settled: the root of r = 1.01 is dt = 0.002.
  OnsetCuts cuts(kTarget, true);
  const double first = cuts.next(0.01, 0.6, 1.002 + 4 * 0.01, true);
  EXPECT_DOUBLE_EQ(first, 0.006);
  EXPECT_NEAR(cuts.next(first, 0.5, 1.002 + 4 * first, true), 0.002, 1e-15);
  EXPECT_FALSE(cuts.locates_at_no_length());
}

TEST(OnsetCuts, SettledAttemptsWhoseLineStaysAboveTheTargetStandOrTakeALastTenth) {
  // r = 1.05 + 2 dt: the settled growth passes the onset at any length.
  for (const bool may_stand : {true, false}) {
    OnsetCuts cuts(kTarget, may_stand);
    const double first = cuts.next(0.01, 0.5, 1.05 + 2 * 0.01, true);
    EXPECT_DOUBLE_EQ(cuts.next(first, 0.5, 1.05 + 2 * first, true), may_stand ? 0.0 : 0.1 * first);
    EXPECT_FALSE(cuts.may_cut());
    // A step of no length after settled cuts starts its onsets with its first pass.
    EXPECT_FALSE(cuts.locates_at_no_length());
  }
}

}  // namespace
}  // namespace rockdd

// The fragment restraint (METHOD.md, loose fragments): which parts of a model are loose, and
// how each is held. A block detached loose gets the weak spring on every node; a part that a
// damage cascade cut loose inside a step, still hinged to the specimen through broken
// elements, gets a statically determinate support on its free rigid modes only.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "engine/damage/fragment_restraint.hpp"
#include "engine/loading/boundary_conditions.hpp"

namespace rockdd {
namespace {

// A 2x1 strip of four triangles, the bottom row of nodes fixed in x and y:
//   3---4---5
//   | 1/|3 /|        element 0 = (0, 1, 4), 1 = (0, 4, 3), 2 = (1, 2, 5), 3 = (1, 5, 4)
//   |/ 0|/ 2|
//   0---1---2
Model strip(std::vector<double> young) {
  Model m;
  m.X = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1};
  m.conn = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  m.young = std::move(young);
  m.damage.assign(4, 0.0);
  m.element_block.assign(4, 0);
  m.node_block.assign(6, 0);
  m.num_blocks = 1;
  return m;
}

BoundaryConditions bottom_fixed() {
  BoundaryConditions bc;
  bc.prescribed = {1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0};
  bc.velocity.assign(12, 0.0);
  bc.equation.assign(12, -1);
  for (std::size_t d = 6; d < 12; ++d) bc.equation[d] = bc.num_equations++;
  return bc;
}

/// The spring stiffness on each dof (0 where there is none), read back through forces().
/// No dof prescribed: every node of the strip free, its equations in dof order.
BoundaryConditions nothing_prescribed() {
  BoundaryConditions bc;
  bc.prescribed.assign(12, 0);
  bc.velocity.assign(12, 0.0);
  bc.equation.resize(12);
  for (std::size_t d = 0; d < 12; ++d) bc.equation[d] = bc.num_equations++;
  return bc;
}

std::vector<double> springs(const FragmentRestraint& restraint) {
  std::vector<double> unit(12, 1.0), force(12, 0.0);
  restraint.forces(unit, force);
  return force;
}

TEST(FragmentRestraint, AHeldSpecimenGetsNoSpring) {
  const FragmentRestraint restraint(strip({1e9, 1e9, 1e9, 1e9}), bottom_fixed(), 1e-6);
  EXPECT_EQ(restraint.num_dofs(), 0u);
}

TEST(FragmentRestraint, APieceHingedByBrokenElementsGetsOneSupportSpringOffItsHinge) {
  // Elements 0 and 3 broke inside a step (w = 1, not detached yet): element 1 still shares
  // node 0 (fixed) with the specimen but no edge, so it can only turn about node 0; element 2
  // keeps two fixed nodes. One spring of support x E0 t (element 1's E0 = 2e9 Pa, t = 1 m)
  // holds the turn, on node 3 or 4, and nothing else is touched: a determinate support.
  Model m = strip({1e9, 2e9, 1e9, 1e9});
  m.damage[0] = m.damage[3] = 1.0;
  const FragmentRestraint restraint(m, bottom_fixed(), 1e-6, 0.5);
  ASSERT_EQ(restraint.num_dofs(), 1u);
  const std::vector<double> k = springs(restraint);
  const auto dof = static_cast<std::size_t>(std::max_element(k.begin(), k.end()) - k.begin());
  EXPECT_TRUE(dof / 2 == 3 || dof / 2 == 4) << "dof " << dof;
  EXPECT_DOUBLE_EQ(k[dof], 0.5 * 2e9);
}

TEST(FragmentRestraint, ALooseDetachedBlockGetsTheWeakSpringOnEveryNode) {
  // Nothing prescribed: the strip is a block loose in all three modes, detached in an earlier
  // step, so every node gets fraction x E0 t / 3 per element corner on both dofs.
  Model m = strip({3e9, 3e9, 3e9, 3e9});
  const BoundaryConditions bc = nothing_prescribed();
  const FragmentRestraint restraint(m, bc, 1e-6);
  EXPECT_EQ(restraint.num_dofs(), 12u);
  const std::vector<double> k = springs(restraint);
  EXPECT_DOUBLE_EQ(k[2 * 0], 2 * 1e-6 * 3e9 / 3.0);  // node 0: corner of elements 0 and 1
  EXPECT_DOUBLE_EQ(k[2 * 4], 3 * 1e-6 * 3e9 / 3.0);  // node 4: corner of elements 0, 1, 3
}

TEST(FragmentRestraint, SpringsAddedInsideAStepStartFromWhereTheyWereAdded) {
  // A support added at increment du holds the part there: no force at du, k (du' - du) after.
  Model m = strip({1e9, 2e9, 1e9, 1e9});
  const FragmentRestraint before(m, bottom_fixed(), 1e-6);
  m.damage[0] = m.damage[3] = 1.0;
  FragmentRestraint after(m, bottom_fixed(), 1e-6);
  std::vector<double> du(12, 0.0);
  for (std::size_t d = 6; d < 12; ++d) du[d] = 1e-6 * static_cast<double>(d);
  after.anchor_new_springs(before, du);
  std::vector<double> force(12, 1.0);
  after.forces(du, force);
  for (const double f : force) EXPECT_EQ(f, 0.0);
  EXPECT_EQ(after.energy(du), 0.0);
  std::vector<double> moved = du;
  for (std::size_t d = 6; d < 12; ++d) moved[d] += 1e-6;
  after.forces(moved, force);
  EXPECT_NEAR(*std::max_element(force.begin(), force.end()), 2e9 * 1e-6, 1e-6);
}

TEST(FragmentRestraint, FollowingHoldsThePartsWhereTheyAreAndRestartHoldsFromTheStepStart) {
  // relax_restraint re-anchors every spring where a settling solve left the parts: no force
  // and no energy at that increment, k (du' - du) past it; the commit then restarts them from
  // the step's start (force k du'). Exact: the springs are linear.
  Model m = strip({3e9, 3e9, 3e9, 3e9});
  const BoundaryConditions bc = nothing_prescribed();
  FragmentRestraint restraint(m, bc, 1e-6);
  const FragmentRestraint fresh = restraint;
  const std::vector<double> k = springs(fresh);  // from unit increments, anchors at 0
  std::vector<double> du(12);
  for (std::size_t d = 0; d < 12; ++d) du[d] = 1e-5 * static_cast<double>(d + 1);
  restraint.follow(du);
  EXPECT_TRUE(restraint.same_springs(fresh));
  std::vector<double> force(12, 1.0);
  restraint.forces(du, force);
  for (const double f : force) EXPECT_EQ(f, 0.0);
  EXPECT_EQ(restraint.energy(du), 0.0);
  std::vector<double> moved = du;
  moved[8] += 2e-6;
  restraint.forces(moved, force);
  EXPECT_DOUBLE_EQ(force[8], k[8] * ((du[8] + 2e-6) - du[8]));
  restraint.restart();
  EXPECT_EQ(restraint, fresh);
  restraint.forces(du, force);
  EXPECT_DOUBLE_EQ(force[8], k[8] * du[8]);
}

}  // namespace
}  // namespace rockdd

// Whether a fractured specimen can still carry its load (engine/damage/load_path): a chain of
// rock that is not fully broken, and of closed contacts, from a node a boundary moves to a node a
// boundary holds in the same direction. The answer is topological, so each case has an exact
// expected value.
#include <gtest/gtest.h>

#include <vector>

#include "engine/contact/contact.hpp"
#include "engine/damage/load_path.hpp"
#include "engine/loading/boundary_conditions.hpp"

namespace rockdd {
namespace {

// A column of two cells, four triangles, the bottom row held in y and the top row moved down:
//   4---5    top: moves in y
//   | 3/|    element 2 = (2, 3, 5), 3 = (2, 5, 4)
//   |/ 2|
//   2---3
//   | 1/|    element 0 = (0, 1, 3), 1 = (0, 3, 2)
//   |/ 0|
//   0---1    bottom: held in y
Model column() {
  Model m;
  m.X = {0, 0, 1, 0, 0, 1, 1, 1, 0, 2, 1, 2};
  m.conn = {0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4};
  m.damage.assign(4, 0.0);
  m.element_block.assign(4, 0);
  m.node_block.assign(6, 0);
  m.num_blocks = 1;
  return m;
}

/// The bottom nodes (0, 1) held in y, the top ones (4, 5) moving in `top_direction` (0 x, 1 y).
BoundaryConditions pressed(int top_direction = 1) {
  BoundaryConditions bc;
  bc.prescribed.assign(12, 0);
  bc.velocity.assign(12, 0.0);
  bc.prescribed[1] = bc.prescribed[3] = 1;
  for (const std::size_t node : {4u, 5u}) {
    bc.prescribed[2 * node + top_direction] = 1;
    bc.velocity[2 * node + top_direction] = -1e-5;
  }
  return bc;
}

/// A contact of vertex p on the edge a->b in `state`.
Contact contact(std::int32_t p, std::int32_t a, std::int32_t b, ContactState state) {
  Contact c;
  c.vertex = p;
  c.a = a;
  c.b = b;
  c.state = state;
  return c;
}

TEST(LoadPath, AnIntactColumnJoinsItsPlatens) {
  EXPECT_TRUE(has_load_path_boundaries(pressed()));
  EXPECT_TRUE(joins_moving_and_fixed_boundaries(column(), pressed(), {}));
}

TEST(LoadPath, AMotionAcrossTheHeldDirectionDrivesNothingThroughTheRock) {
  // The top moves in x, the bottom is held in y only: no force along the motion reaches a
  // support, whatever the rock between them.
  EXPECT_FALSE(has_load_path_boundaries(pressed(0)));
  EXPECT_FALSE(joins_moving_and_fixed_boundaries(column(), pressed(0), {}));
}

TEST(LoadPath, ARowOfBrokenElementsCutsIt) {
  Model m = column();
  m.damage[0] = m.damage[1] = 1.0;  // the lower cell broken through
  EXPECT_FALSE(joins_moving_and_fixed_boundaries(m, pressed(), {}));
  m.damage[1] = 0.999;  // one element left, nearly broken: it still joins its nodes
  EXPECT_TRUE(joins_moving_and_fixed_boundaries(m, pressed(), {}));
}

TEST(LoadPath, AClosedContactAcrossTheCrackJoinsItAndAnOpenOneDoesNot) {
  // The upper cell cut off as its own piece: its nodes 2 and 3 split into 6 and 7, and its
  // corner 6 touches the lower cell's top edge 3->2.
  Model m = column();
  m.X.insert(m.X.end(), {0, 1, 1, 1});
  m.conn = {0, 1, 3, 0, 3, 2, 6, 7, 5, 6, 5, 4};
  BoundaryConditions bc = pressed();
  bc.prescribed.resize(16, 0);
  bc.velocity.resize(16, 0.0);
  EXPECT_FALSE(joins_moving_and_fixed_boundaries(m, bc, {}));
  for (const ContactState state : {ContactState::sliding, ContactState::locked})
    EXPECT_TRUE(joins_moving_and_fixed_boundaries(m, bc, std::vector{contact(6, 3, 2, state)}));
  EXPECT_FALSE(
      joins_moving_and_fixed_boundaries(m, bc, std::vector{contact(6, 3, 2, ContactState::open)}));
}

TEST(LoadPath, APieceHangingFromTheMovingPlatenCarriesNothing) {
  // Only the upper cell is left and nothing below touches it: it touches the moving boundary
  // alone, held sideways by nothing (the ucs_confined.toml case in plane stress).
  Model m = column();
  m.damage[0] = m.damage[1] = 1.0;
  BoundaryConditions bc = pressed();
  bc.prescribed[8] = bc.prescribed[10] = 1;  // the top also held in x: still no path in y
  EXPECT_FALSE(joins_moving_and_fixed_boundaries(m, bc, {}));
}

}  // namespace
}  // namespace rockdd

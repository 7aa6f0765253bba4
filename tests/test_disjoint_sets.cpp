// Union-find (engine/common/disjoint_sets.hpp): which members share a set, and that a set's
// representative is its lowest member whatever order the joins come in, which is what makes
// blocks and parts numbered from it the same for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "engine/common/disjoint_sets.hpp"

namespace rockdd {
namespace {

TEST(DisjointSets, SingletonsRepresentThemselves) {
  DisjointSets sets(5);
  for (std::int32_t i = 0; i < 5; ++i) EXPECT_EQ(sets.find(i), i);
}

TEST(DisjointSets, JoinsAreTransitiveAndLeaveOthersApart) {
  DisjointSets sets(6);
  sets.join(4, 2);
  sets.join(2, 5);
  sets.join(1, 3);
  EXPECT_EQ(sets.find(5), sets.find(4));
  EXPECT_EQ(sets.find(3), sets.find(1));
  EXPECT_NE(sets.find(5), sets.find(3));
  EXPECT_EQ(sets.find(0), 0);
  sets.join(5, 5);  // a member with itself changes nothing
  sets.join(4, 2);  // nor does a pair already together
  EXPECT_EQ(sets.find(2), 2);
}

TEST(DisjointSets, TheLowestMemberRepresentsItsSetWhateverTheOrderOfTheJoins) {
  // A chain 0-1-...-9 and a chain 10-...-19, their joins shuffled: every member of each chain
  // finds the chain's lowest member.
  std::vector<std::array<std::int32_t, 2>> joins;
  for (std::int32_t i = 0; i < 9; ++i) {
    joins.push_back({i + 1, i});
    joins.push_back({11 + i, 10 + i});
  }
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    std::shuffle(joins.begin(), joins.end(), random);
    DisjointSets sets(20);
    for (const auto& [a, b] : joins) sets.join(a, b);
    for (std::int32_t i = 0; i < 20; ++i) EXPECT_EQ(sets.find(i), i < 10 ? 0 : 10) << i;
  }
}

TEST(DisjointSets, ResetStartsSingletonsAgain) {
  DisjointSets sets(4);
  sets.join(0, 3);
  sets.reset(3);
  for (std::int32_t i = 0; i < 3; ++i) EXPECT_EQ(sets.find(i), i);
  sets.reset(8);
  sets.join(7, 6);
  EXPECT_EQ(sets.find(7), 6);
  EXPECT_EQ(sets.find(3), 3);
}

}  // namespace
}  // namespace rockdd

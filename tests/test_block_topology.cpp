// Blocks and node splitting (METHOD.md, "Fracture"): elements stay joined only through
// intact edges; a split node keeps one id per connected group around it.
#include <gtest/gtest.h>

#include <set>

#include "engine/common/errors.hpp"
#include "engine/model/block_topology.hpp"
#include "engine/model/edge_adjacency.hpp"

namespace rockdd {
namespace {

// A 2x1 strip of four triangles:   3---4---5
//                                  | / | / |
//                                  0---1---2
const std::vector<std::int32_t> kStrip = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};

TEST(EdgeAdjacency, FindsSharedEdgesBothWays) {
  const EdgeAdjacency adj = build_edge_adjacency(kStrip, "strip");
  // Element 0 edge 2 (4-0) is shared with element 1 edge 0 (0-4).
  EXPECT_EQ(adj.neighbor[3 * 0 + 2], 1);
  EXPECT_EQ(adj.neighbor[3 * 1 + 0], 0);
  // Element 0 edge 1 (1-4) is shared with element 3 edge 2 (4-1).
  EXPECT_EQ(adj.neighbor[3 * 0 + 1], 3);
  EXPECT_EQ(adj.neighbor[3 * 3 + 2], 0);
  int boundary = 0;
  for (const auto n : adj.neighbor) boundary += n < 0;
  EXPECT_EQ(boundary, 6);  // the outline of the strip has six edges
}

TEST(EdgeAdjacency, RejectsNonManifoldEdges) {
  const std::vector<std::int32_t> fan = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  EXPECT_THROW(build_edge_adjacency(fan, "fan"), InputError);
}

TEST(EdgeAdjacency, DroppingSplitEdgesGivesTheAdjacencyOfTheSplitMesh) {
  // Cut edge 1-4: nodes 1 and 4 split, and the kept adjacency is exactly what the sort finds
  // on the new connectivity (elements 0 and 3 no longer neighbours, the rest unchanged).
  EdgeAdjacency kept = build_edge_adjacency(kStrip, "strip");
  std::vector<std::uint8_t> intact(kStrip.size(), 1);
  intact[3 * 0 + 1] = 0;
  intact[3 * 3 + 2] = 0;
  const BlockTopology topo = form_blocks(kStrip, 6, kept, intact);
  drop_split_edges(topo.conn, kept);
  const EdgeAdjacency rebuilt = build_edge_adjacency(topo.conn, "split strip");
  EXPECT_EQ(kept.neighbor, rebuilt.neighbor);
  EXPECT_EQ(kept.neighbor_edge, rebuilt.neighbor_edge);
  EXPECT_EQ(kept.neighbor[3 * 0 + 1], -1);
  EXPECT_EQ(kept.neighbor[3 * 0 + 2], 1);
}

TEST(BlockTopology, IntactMeshIsOneBlockWithoutSplits) {
  const EdgeAdjacency adj = build_edge_adjacency(kStrip, "strip");
  const std::vector<std::uint8_t> intact(kStrip.size(), 1);
  const BlockTopology topo = form_blocks(kStrip, 6, adj, intact);
  EXPECT_EQ(topo.num_blocks, 1);
  EXPECT_EQ(topo.node_origin.size(), 6u);
  EXPECT_EQ(topo.conn, kStrip);
}

TEST(BlockTopology, CuttingTheMiddleEdgeSplitsBothItsNodes) {
  const EdgeAdjacency adj = build_edge_adjacency(kStrip, "strip");
  std::vector<std::uint8_t> intact(kStrip.size(), 1);
  // Cut edge 1-4 on both sides: elements {0,1} and {2,3} become two blocks.
  intact[3 * 0 + 1] = 0;
  intact[3 * 3 + 2] = 0;
  const BlockTopology topo = form_blocks(kStrip, 6, adj, intact);
  EXPECT_EQ(topo.num_blocks, 2);
  EXPECT_EQ(topo.element_block[0], topo.element_block[1]);
  EXPECT_EQ(topo.element_block[2], topo.element_block[3]);
  EXPECT_NE(topo.element_block[0], topo.element_block[2]);
  ASSERT_EQ(topo.node_origin.size(), 8u);  // nodes 1 and 4 were duplicated
  EXPECT_EQ(topo.node_origin[6], 1);
  EXPECT_EQ(topo.node_origin[7], 4);
  // No node is shared between the blocks any more.
  std::set<std::int32_t> left(topo.conn.begin(), topo.conn.begin() + 6);
  for (int s = 6; s < 12; ++s) EXPECT_EQ(left.count(topo.conn[s]), 0u) << s;
}

TEST(BlockTopology, ElementDetachedAloneBecomesItsOwnBlock) {
  const EdgeAdjacency adj = build_edge_adjacency(kStrip, "strip");
  std::vector<std::uint8_t> intact(kStrip.size(), 1);
  for (int k = 0; k < 3; ++k) {  // element 3 detaches: all its edges stop binding
    intact[3 * 3 + k] = 0;
    if (adj.neighbor[3 * 3 + k] >= 0)
      intact[3 * adj.neighbor[3 * 3 + k] + adj.neighbor_edge[3 * 3 + k]] = 0;
  }
  const BlockTopology topo = form_blocks(kStrip, 6, adj, intact);
  // Element 2 was held only through edge 1-5 of element 3, so it is freed too:
  // blocks {0, 1}, {2}, {3}. Node 1 is in all three (2 copies more), node 4 in {0,1} and {3},
  // node 5 in {2} and {3}: 6 + 4 nodes.
  EXPECT_EQ(topo.num_blocks, 3);
  EXPECT_EQ(topo.node_origin.size(), 10u);
  EXPECT_EQ(topo.element_block[0], topo.element_block[1]);
  EXPECT_NE(topo.element_block[2], topo.element_block[3]);
}

TEST(BlockTopology, TwoTrianglesTouchingAtOneVertexDoNotShareIt) {
  // Bow tie: triangles (0,1,2) and (0,3,4) share node 0 only.
  const std::vector<std::int32_t> bow = {0, 1, 2, 0, 3, 4};
  const EdgeAdjacency adj = build_edge_adjacency(bow, "bow");
  const std::vector<std::uint8_t> intact(bow.size(), 1);
  const BlockTopology topo = form_blocks(bow, 5, adj, intact);
  EXPECT_EQ(topo.num_blocks, 2);
  EXPECT_EQ(topo.node_origin.size(), 6u);
  EXPECT_NE(topo.conn[0], topo.conn[3]);
}

}  // namespace
}  // namespace rockdd

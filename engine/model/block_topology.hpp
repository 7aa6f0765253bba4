#pragma once
// Blocks from intact edges: the grouping that both the scene (separate bodies, joints)
// and fracture (detached elements) use.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/model/edge_adjacency.hpp"

namespace rockdd {

/// Connectivity with split nodes, and the block of each element.
struct BlockTopology {
  std::vector<std::int32_t> conn;         // 3 per element, split node ids
  std::vector<std::int32_t> node_origin;  // new node -> node it came from
  std::vector<std::int32_t> element_block;
  std::int32_t num_blocks = 0;
};

/// A block is a maximal set of elements joined through intact shared edges. Two elements
/// keep sharing a node only if they are connected around that node through intact edges;
/// otherwise the node is split. The first group at a node keeps its id; the others get new
/// ids after the existing ones, in node order, so the result does not depend on threads.
/// `edge_intact[3e+k]` says whether edge k of element e still binds it to its neighbour.
BlockTopology form_blocks(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                          const EdgeAdjacency& adjacency,
                          std::span<const std::uint8_t> edge_intact);

}  // namespace rockdd

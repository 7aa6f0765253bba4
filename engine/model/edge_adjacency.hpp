#pragma once
// Which element lies across each edge of each element.
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// Edge k of element e joins corners k and (k+1) % 3. neighbor[3e+k] is the element across
/// it (-1 on the boundary) and neighbor_edge[3e+k] that element's local edge index.
struct EdgeAdjacency {
  std::vector<std::int32_t> neighbor;
  std::vector<std::int8_t> neighbor_edge;
};

/// Finds shared edges by sorting edge keys. Throws InputError (where = `source`) when an
/// edge is shared by more than two elements (a non-manifold mesh).
EdgeAdjacency build_edge_adjacency(std::span<const std::int32_t> conn, const char* source);

/// After nodes split (elements keep their numbers and corners, some corners become copies):
/// forgets the neighbours that no longer share both nodes of the edge. What remains is what
/// build_edge_adjacency gives for the new connectivity, without its sort.
void drop_split_edges(std::span<const std::int32_t> conn, EdgeAdjacency& adjacency);

/// Elements incident to each node, as a compressed list: elements of node n are
/// element[offset[n] .. offset[n+1]), in increasing element order.
struct NodeIncidence {
  std::vector<std::int32_t> offset;
  std::vector<std::int32_t> element;
};

/// Node-to-element incidence of a connectivity (3 nodes per element).
NodeIncidence build_node_incidence(std::span<const std::int32_t> conn, std::int32_t num_nodes);

}  // namespace rockdd

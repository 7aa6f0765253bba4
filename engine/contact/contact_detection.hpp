#pragma once
// Contact detection between blocks: the boundary of every block, a parallel broad phase
// over edge bounding boxes, and a KD-tree (nanoflann) narrow phase over boundary vertices.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// The free boundary of all blocks: edges with no intact neighbour across them.
struct BlockBoundary {
  std::vector<std::int32_t> edge_nodes;    // 2 per edge, a->b counter-clockwise (body on the left)
  std::vector<std::int32_t> edge_element;  // element that owns each edge
  std::vector<std::int32_t> edge_block;    // block of each edge
  std::vector<std::int32_t> vertices;      // boundary nodes, sorted, unique
  std::vector<std::int32_t> vertex_block;  // block of each boundary vertex (same order)
};

/// A vertex of one block near an edge of another: a candidate vertex-edge contact.
struct ContactCandidate {
  std::int32_t vertex = -1;  // node id
  std::int32_t edge = -1;    // index into BlockBoundary's edges
};

/// Which bodies may touch: allowed[body_a * num_bodies + body_b] (symmetric).
struct ContactRules {
  std::int32_t num_bodies = 0;
  std::vector<std::uint8_t> allowed;
  std::vector<std::int32_t> block_body;  // body of each block
  std::vector<std::uint8_t> inert;       // per block (empty: none): takes no part in contact
};

/// Boundary edges and vertices of the model's blocks (edges whose neighbour is absent or in
/// another block). `intact` is not needed: blocks own their nodes, so a shared edge across
/// two blocks never exists in the connectivity.
BlockBoundary extract_block_boundary(const Model& model);

/// The same, from the edge adjacency of model.conn that the caller already keeps (the
/// fracture's, which follows every node split): no sort of the edges.
BlockBoundary extract_block_boundary(const Model& model, const EdgeAdjacency& adjacency);

/// Every (vertex, edge) pair of different blocks allowed by `rules` with the vertex within
/// `reach` of the edge segment at current positions (`positions`, 2 per node). For each
/// vertex and each other block only the edge with the largest signed gap is kept (at a convex
/// corner: the face the vertex is least behind). Sorted by (vertex, edge):
/// the same list whatever the thread count. `inflation` (the step's largest displacement)
/// only widens the broad phase's boxes: the list depends on `reach` alone.
std::vector<ContactCandidate> detect_contacts(const BlockBoundary& boundary,
                                              std::span<const double> positions,
                                              const ContactRules& rules, double reach,
                                              double inflation = 0.0);

}  // namespace rockdd

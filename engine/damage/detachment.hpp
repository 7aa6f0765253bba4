#pragma once
// Fracture (METHOD.md "Fracture: damaged elements become blocks"): an element whose damage
// reaches its threshold detaches, its three edges stop binding it, nodes split so that
// elements keep sharing a node only through intact edges, and blocks are regrouped.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// What detaching changed: node_origin[n] is the node that new node n came from (the
/// identity for nodes that were not split); empty when nothing detached.
struct Detachment {
  std::int32_t detached = 0;              // elements detached now
  std::vector<std::int32_t> node_origin;  // per node of the new topology
};

/// Detaches every element with damage above `threshold[e]` (w > 0 for threshold 0) that
/// `detached` does not already mark, and marks it. Node fields of `model` (X, u, v, mass,
/// block) follow the split nodes: copies keep their node's displacement and velocity, and
/// masses are the lumped masses of the new topology, so mass and momentum are conserved.
/// Named curves and points follow too. Deterministic.
Detachment detach_damaged_elements(Model& model, std::span<const double> threshold,
                                   std::vector<std::uint8_t>& detached);

/// The same with the edge adjacency of model.conn given, and kept: on return it is the
/// adjacency of the split connectivity (drop_split_edges).
Detachment detach_damaged_elements(Model& model, std::span<const double> threshold,
                                   std::vector<std::uint8_t>& detached, EdgeAdjacency& adjacency);

/// field_new[n] = field[origin[n]] for a 2-per-node field.
void follow_split_nodes(std::span<const std::int32_t> node_origin, std::vector<double>& field);

}  // namespace rockdd

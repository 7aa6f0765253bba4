#include "engine/damage/detachment.hpp"

#include <algorithm>

#include "engine/model/block_topology.hpp"
#include "engine/model/edge_adjacency.hpp"

namespace rockdd {

void follow_split_nodes(std::span<const std::int32_t> node_origin, std::vector<double>& field) {
  std::vector<double> out(2 * node_origin.size());
  for (std::size_t n = 0; n < node_origin.size(); ++n) {
    out[2 * n] = field[2 * static_cast<std::size_t>(node_origin[n])];
    out[2 * n + 1] = field[2 * static_cast<std::size_t>(node_origin[n]) + 1];
  }
  field = std::move(out);
}

Detachment detach_damaged_elements(Model& model, std::span<const double> threshold,
                                   std::vector<std::uint8_t>& detached) {
  EdgeAdjacency adjacency = build_edge_adjacency(model.conn, "fracture");
  return detach_damaged_elements(model, threshold, detached, adjacency);
}

Detachment detach_damaged_elements(Model& model, std::span<const double> threshold,
                                   std::vector<std::uint8_t>& detached, EdgeAdjacency& adjacency) {
  Detachment result;
  const std::int32_t num_elements = model.num_elements();
  detached.resize(static_cast<std::size_t>(num_elements), 0);
  for (std::int32_t e = 0; e < num_elements; ++e)
    if (!detached[e] && (model.damage[e] > threshold[e] || model.damage[e] >= 1.0)) {
      detached[e] = 1;
      ++result.detached;
    }
  if (result.detached == 0) return result;

  // An edge binds its two elements while neither is detached.
  std::vector<std::uint8_t> intact(3 * static_cast<std::size_t>(num_elements), 0);
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t other = adjacency.neighbor[3 * e + k];
      intact[3 * e + k] = other >= 0 && !detached[e] && !detached[other];
    }
  BlockTopology topology = form_blocks(model.conn, model.num_nodes(), adjacency, intact);

  // Named curves keep their element sides: the side's nodes are the element's new corners.
  const std::vector<std::int32_t> old_conn = model.conn;
  auto corner = [&](std::int32_t e, std::int32_t node) {
    for (int k = 0; k < 3; ++k)
      if (old_conn[3 * e + k] == node) return topology.conn[3 * e + k];
    return node;
  };
  for (auto& [name, edges] : model.sets.curve_edges) {
    const auto& owners = model.sets.curve_edge_element.at(name);
    for (std::size_t i = 0; i < owners.size(); ++i) {
      edges[2 * i] = corner(owners[i], edges[2 * i]);
      edges[2 * i + 1] = corner(owners[i], edges[2 * i + 1]);
    }
  }
  // Named points stand for every copy of their nodes.
  for (auto& [name, nodes] : model.sets.points) {
    std::vector<std::int32_t> sorted = nodes, copies;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t n = 0; n < topology.node_origin.size(); ++n)
      if (std::binary_search(sorted.begin(), sorted.end(), topology.node_origin[n]))
        copies.push_back(static_cast<std::int32_t>(n));
    nodes = std::move(copies);
  }

  model.conn = std::move(topology.conn);
  drop_split_edges(model.conn, adjacency);
  model.element_block = std::move(topology.element_block);
  model.num_blocks = topology.num_blocks;
  follow_split_nodes(topology.node_origin, model.X);
  follow_split_nodes(topology.node_origin, model.u);
  follow_split_nodes(topology.node_origin, model.v);
  model.node_block.assign(topology.node_origin.size(), -1);
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) model.node_block[model.conn[3 * e + k]] = model.element_block[e];
  model.node_mass = lumped_node_mass(model);
  std::vector<std::int32_t> root(topology.node_origin.size());
  for (std::size_t n = 0; n < root.size(); ++n) root[n] = model.node_root[topology.node_origin[n]];
  model.node_root = std::move(root);
  result.node_origin = std::move(topology.node_origin);
  return result;
}

}  // namespace rockdd

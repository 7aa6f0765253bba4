#include "engine/model/block_topology.hpp"

#include <tbb/parallel_for.h>

#include <numeric>

#include "engine/common/disjoint_sets.hpp"

namespace rockdd {
namespace {

bool binds(const EdgeAdjacency& adj, std::span<const std::uint8_t> intact, std::size_t slot) {
  return adj.neighbor[slot] >= 0 && intact[slot] != 0;
}

}  // namespace

BlockTopology form_blocks(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                          const EdgeAdjacency& adjacency,
                          std::span<const std::uint8_t> edge_intact) {
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  BlockTopology topo;

  DisjointSets blocks(static_cast<std::size_t>(num_elements));
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k)
      if (binds(adjacency, edge_intact, 3 * static_cast<std::size_t>(e) + k))
        blocks.join(e, adjacency.neighbor[3 * e + k]);
  topo.element_block.resize(static_cast<std::size_t>(num_elements));
  std::vector<std::int32_t> block_of_root(static_cast<std::size_t>(num_elements), -1);
  for (std::int32_t e = 0; e < num_elements; ++e) {
    const std::int32_t r = blocks.find(e);
    if (block_of_root[r] < 0) block_of_root[r] = topo.num_blocks++;
    topo.element_block[e] = block_of_root[r];
  }

  // Around each node, group the incident elements that are joined through an intact edge
  // containing that node. Each group after the first needs a node of its own.
  const NodeIncidence inc = build_node_incidence(conn, num_nodes);
  std::vector<std::int32_t> group_of_slot(conn.size(), 0);  // local group index per corner
  std::vector<std::int32_t> extra_groups(static_cast<std::size_t>(num_nodes), 0);
  tbb::parallel_for(tbb::blocked_range<std::int32_t>(0, num_nodes, 1024), [&](auto range) {
    DisjointSets local;
    std::vector<std::int32_t> local_group;
    for (std::int32_t n = range.begin(); n != range.end(); ++n) {
      const std::int32_t begin = inc.offset[n], count = inc.offset[n + 1] - begin;
      local.reset(static_cast<std::size_t>(count));
      auto local_index = [&](std::int32_t element) {
        for (std::int32_t i = 0; i < count; ++i)
          if (inc.element[begin + i] == element) return i;
        return std::int32_t{-1};
      };
      for (std::int32_t i = 0; i < count; ++i) {
        const std::int32_t e = inc.element[begin + i];
        for (int k = 0; k < 3; ++k) {
          const std::size_t slot = 3 * static_cast<std::size_t>(e) + k;
          const bool touches_node = conn[slot] == n || conn[3 * e + (k + 1) % 3] == n;
          if (!touches_node || !binds(adjacency, edge_intact, slot)) continue;
          const std::int32_t j = local_index(adjacency.neighbor[slot]);
          local.join(i, j);
        }
      }
      local_group.assign(count, -1);
      std::int32_t groups = 0;
      for (std::int32_t i = 0; i < count; ++i) {
        const std::int32_t r = local.find(i);
        if (local_group[r] < 0) local_group[r] = groups++;
        const std::int32_t e = inc.element[begin + i];
        for (int c = 0; c < 3; ++c)
          if (conn[3 * e + c] == n)
            group_of_slot[3 * static_cast<std::size_t>(e) + c] = local_group[r];
      }
      extra_groups[n] = groups - 1;
    }
  });

  std::vector<std::int32_t> first_extra(static_cast<std::size_t>(num_nodes) + 1, num_nodes);
  for (std::int32_t n = 0; n < num_nodes; ++n)
    first_extra[n + 1] = first_extra[n] + extra_groups[n];
  const std::int32_t total_nodes = first_extra[num_nodes];
  topo.node_origin.resize(static_cast<std::size_t>(total_nodes));
  std::iota(topo.node_origin.begin(), topo.node_origin.begin() + num_nodes, 0);
  for (std::int32_t n = 0; n < num_nodes; ++n)
    for (std::int32_t g = 0; g < extra_groups[n]; ++g) topo.node_origin[first_extra[n] + g] = n;

  topo.conn.resize(conn.size());
  for (std::size_t s = 0; s < conn.size(); ++s) {
    const std::int32_t n = conn[s], g = group_of_slot[s];
    topo.conn[s] = g == 0 ? n : first_extra[n] + g - 1;
  }
  return topo;
}

}  // namespace rockdd

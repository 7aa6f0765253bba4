#include "engine/model/edge_adjacency.hpp"

#include <tbb/parallel_sort.h>

#include <string>

#include "engine/common/errors.hpp"

namespace rockdd {

EdgeAdjacency build_edge_adjacency(std::span<const std::int32_t> conn, const char* source) {
  const auto num_slots = static_cast<std::int64_t>(conn.size());
  // One record per element edge: (low node, high node, slot). Sorting brings the two sides
  // of a shared edge together; the slot makes every record unique, so the order is total.
  struct EdgeRecord {
    std::int32_t lo, hi;
    std::int64_t slot;
    bool operator<(const EdgeRecord& o) const {
      if (lo != o.lo) return lo < o.lo;
      if (hi != o.hi) return hi < o.hi;
      return slot < o.slot;
    }
  };
  std::vector<EdgeRecord> records(static_cast<std::size_t>(num_slots));
  for (std::int64_t s = 0; s < num_slots; ++s) {
    const std::int64_t e = s / 3;
    const int k = static_cast<int>(s % 3);
    const std::int32_t a = conn[3 * e + k];
    const std::int32_t b = conn[3 * e + (k + 1) % 3];
    records[s] = {std::min(a, b), std::max(a, b), s};
  }
  tbb::parallel_sort(records.begin(), records.end());

  EdgeAdjacency adj;
  adj.neighbor.assign(static_cast<std::size_t>(num_slots), -1);
  adj.neighbor_edge.assign(static_cast<std::size_t>(num_slots), -1);
  std::size_t i = 0;
  while (i < records.size()) {
    std::size_t j = i + 1;
    while (j < records.size() && records[j].lo == records[i].lo && records[j].hi == records[i].hi)
      ++j;
    if (j - i > 2) {
      throw InputError(source, "mesh",
                       "edge between nodes " + std::to_string(records[i].lo) + " and " +
                           std::to_string(records[i].hi) + " is shared by " +
                           std::to_string(j - i) + " triangles (expected a manifold mesh)");
    }
    if (j - i == 2) {
      const std::int64_t s0 = records[i].slot, s1 = records[i + 1].slot;
      adj.neighbor[s0] = static_cast<std::int32_t>(s1 / 3);
      adj.neighbor_edge[s0] = static_cast<std::int8_t>(s1 % 3);
      adj.neighbor[s1] = static_cast<std::int32_t>(s0 / 3);
      adj.neighbor_edge[s1] = static_cast<std::int8_t>(s0 % 3);
    }
    i = j;
  }
  return adj;
}

void drop_split_edges(std::span<const std::int32_t> conn, EdgeAdjacency& adjacency) {
  const std::size_t num_slots = conn.size();
  for (std::size_t s = 0; s < num_slots; ++s) {
    const std::int32_t other = adjacency.neighbor[s];
    if (other < 0) continue;
    const std::size_t e = s / 3, k = s % 3;
    const auto j = static_cast<std::size_t>(static_cast<std::uint8_t>(adjacency.neighbor_edge[s]));
    const auto o = static_cast<std::size_t>(other);
    // The same edge seen from the other side runs the other way round.
    if (conn[3 * o + j] == conn[3 * e + (k + 1) % 3] &&
        conn[3 * o + (j + 1) % 3] == conn[3 * e + k])
      continue;
    adjacency.neighbor[s] = -1;
    adjacency.neighbor_edge[s] = -1;
  }
}

NodeIncidence build_node_incidence(std::span<const std::int32_t> conn, std::int32_t num_nodes) {
  NodeIncidence inc;
  inc.offset.assign(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (const std::int32_t n : conn) ++inc.offset[n + 1];
  for (std::int32_t n = 0; n < num_nodes; ++n) inc.offset[n + 1] += inc.offset[n];
  inc.element.resize(conn.size());
  std::vector<std::int32_t> fill(inc.offset.begin(), inc.offset.end() - 1);
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) inc.element[fill[conn[3 * e + k]]++] = e;
  return inc;
}

}  // namespace rockdd

#include "engine/mesh/node_ordering.hpp"

#include <algorithm>
#include <utility>

namespace rockdd {

namespace {

/// Node adjacency in compressed rows: neighbours of n are column[row[n] .. row[n+1]).
struct Graph {
  std::vector<std::int32_t> row;
  std::vector<std::int32_t> column;
  std::int32_t degree(std::int32_t n) const { return row[n + 1] - row[n]; }
};

Graph side_graph(std::size_t num_nodes, std::span<const std::int32_t> triangles) {
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  pairs.reserve(2 * triangles.size());
  for (std::size_t e = 0; e + 2 < triangles.size(); e += 3)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = triangles[e + k], b = triangles[e + (k + 1) % 3];
      pairs.emplace_back(a, b);
      pairs.emplace_back(b, a);
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Graph graph;
  graph.row.assign(num_nodes + 1, 0);
  graph.column.reserve(pairs.size());
  for (const auto& [a, b] : pairs) {
    ++graph.row[a + 1];
    graph.column.push_back(b);
  }
  for (std::size_t n = 0; n < num_nodes; ++n) graph.row[n + 1] += graph.row[n];
  return graph;
}

/// Nodes in breadth-first order from a root, with where the deepest level starts.
struct LevelStructure {
  std::vector<std::int32_t> order;
  std::size_t last_level_begin = 0;
  int depth = 0;
};

/// Breadth-first levels from `root`; `stamp` marks visits with `pass` so no clearing is needed.
LevelStructure levels_from(const Graph& graph, std::int32_t root, std::vector<std::int32_t>& stamp,
                           std::int32_t pass) {
  LevelStructure levels;
  levels.order.push_back(root);
  stamp[root] = pass;
  std::size_t level_end = 1;
  while (true) {
    ++levels.depth;
    for (std::size_t i = levels.last_level_begin; i < level_end; ++i) {
      const std::int32_t n = levels.order[i];
      for (std::int32_t j = graph.row[n]; j < graph.row[n + 1]; ++j)
        if (stamp[graph.column[j]] != pass) {
          stamp[graph.column[j]] = pass;
          levels.order.push_back(graph.column[j]);
        }
    }
    if (levels.order.size() == level_end) return levels;
    levels.last_level_begin = level_end;
    level_end = levels.order.size();
  }
}

/// George–Liu: move to a lowest-degree node of the deepest level while that adds levels.
std::int32_t pseudo_peripheral_node(const Graph& graph, std::int32_t start,
                                    std::vector<std::int32_t>& stamp, std::int32_t& pass) {
  std::int32_t root = start;
  LevelStructure levels = levels_from(graph, root, stamp, ++pass);
  while (true) {
    const auto last = levels.order.begin() + static_cast<std::ptrdiff_t>(levels.last_level_begin);
    const std::int32_t candidate =
        *std::min_element(last, levels.order.end(), [&](std::int32_t a, std::int32_t b) {
          return std::pair(graph.degree(a), a) < std::pair(graph.degree(b), b);
        });
    LevelStructure next = levels_from(graph, candidate, stamp, ++pass);
    if (next.depth <= levels.depth) return root;
    root = candidate;
    levels = std::move(next);
  }
}

/// Cuthill–McKee order of the part holding `root`, appended to `order`: breadth first,
/// each node's new neighbours by increasing degree.
void append_cuthill_mckee(const Graph& graph, std::int32_t root, std::vector<char>& numbered,
                          std::vector<std::int32_t>& order) {
  numbered[root] = 1;
  std::size_t head = order.size();
  order.push_back(root);
  while (head < order.size()) {
    const std::int32_t n = order[head++];
    const std::size_t first = order.size();
    for (std::int32_t j = graph.row[n]; j < graph.row[n + 1]; ++j)
      if (!numbered[graph.column[j]]) {
        numbered[graph.column[j]] = 1;
        order.push_back(graph.column[j]);
      }
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(first), order.end(),
              [&](std::int32_t a, std::int32_t b) {
                return std::pair(graph.degree(a), a) < std::pair(graph.degree(b), b);
              });
  }
}

}  // namespace

std::vector<std::int32_t> reverse_cuthill_mckee(std::size_t num_nodes,
                                                std::span<const std::int32_t> triangles) {
  const Graph graph = side_graph(num_nodes, triangles);
  std::vector<std::int32_t> stamp(num_nodes, 0);
  std::int32_t pass = 0;
  std::vector<char> numbered(num_nodes, 0);
  std::vector<std::int32_t> order;
  order.reserve(num_nodes);
  for (std::size_t n = 0; n < num_nodes; ++n)
    if (!numbered[n])
      append_cuthill_mckee(graph,
                           pseudo_peripheral_node(graph, static_cast<std::int32_t>(n), stamp, pass),
                           numbered, order);
  std::vector<std::int32_t> new_number(num_nodes);
  for (std::size_t k = 0; k < num_nodes; ++k)
    new_number[order[k]] = static_cast<std::int32_t>(num_nodes - 1 - k);
  return new_number;
}

}  // namespace rockdd

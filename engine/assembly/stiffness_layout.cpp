#include "engine/assembly/stiffness_layout.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "engine/model/edge_adjacency.hpp"

namespace rockdd {

StiffnessLayout build_sparsity_pattern(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                                       std::span<const std::int32_t> equation) {
  const NodeIncidence inc = build_node_incidence(conn, num_nodes);

  // Neighbour nodes of each node (itself included), sorted: the node graph of the mesh, as a
  // compressed list built in two passes (count, then fill) without a container per node.
  auto gather_neighbours = [&](std::int32_t n, std::int32_t* out) {
    std::int32_t count = 0;
    for (std::int32_t i = inc.offset[n]; i < inc.offset[n + 1]; ++i)
      for (int k = 0; k < 3; ++k) out[count++] = conn[3 * inc.element[i] + k];
    std::sort(out, out + count);
    return static_cast<std::int32_t>(std::unique(out, out + count) - out);
  };
  std::int32_t max_incident = 0;
  for (std::int32_t n = 0; n < num_nodes; ++n)
    max_incident = std::max(max_incident, inc.offset[n + 1] - inc.offset[n]);
  StiffnessLayout layout;
  std::vector<std::int32_t>& neighbour_offset = layout.neighbours.offset;
  neighbour_offset.assign(static_cast<std::size_t>(num_nodes) + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::int32_t>(0, num_nodes, 512), [&](auto range) {
    std::vector<std::int32_t> scratch(3 * static_cast<std::size_t>(max_incident));
    for (std::int32_t n = range.begin(); n != range.end(); ++n)
      neighbour_offset[n + 1] = gather_neighbours(n, scratch.data());
  });
  for (std::int32_t n = 0; n < num_nodes; ++n) neighbour_offset[n + 1] += neighbour_offset[n];
  std::vector<std::int32_t>& neighbour = layout.neighbours.node;
  neighbour.resize(static_cast<std::size_t>(neighbour_offset[num_nodes]));
  tbb::parallel_for(tbb::blocked_range<std::int32_t>(0, num_nodes, 512), [&](auto range) {
    std::vector<std::int32_t> scratch(3 * static_cast<std::size_t>(max_incident));
    for (std::int32_t n = range.begin(); n != range.end(); ++n) {
      const std::int32_t count = gather_neighbours(n, scratch.data());
      std::copy(scratch.begin(), scratch.begin() + count, neighbour.begin() + neighbour_offset[n]);
    }
  });

  // Column j of the upper triangle holds the equations i <= j of the neighbour dofs.
  // Equations increase with dof index, so walking sorted neighbours yields sorted rows.
  std::int32_t num_equations = 0;
  for (const std::int32_t eq : equation) num_equations = std::max(num_equations, eq + 1);
  std::vector<std::int32_t> dof_of_equation(static_cast<std::size_t>(num_equations));
  for (std::size_t d = 0; d < equation.size(); ++d)
    if (equation[d] >= 0) dof_of_equation[equation[d]] = static_cast<std::int32_t>(d);

  SparsityPattern& p = layout.pattern;
  p.n = num_equations;
  p.col_ptr.assign(static_cast<std::size_t>(num_equations) + 1, 0);
  auto for_each_row = [&](std::int32_t col, auto&& visit) {
    const std::int32_t node = dof_of_equation[col] / 2;
    for (std::int32_t q = neighbour_offset[node]; q < neighbour_offset[node + 1]; ++q)
      for (int c = 0; c < 2; ++c) {
        const std::int32_t m = neighbour[q];
        const std::int32_t row = equation[2 * m + c];
        if (row >= 0 && row <= col) visit(row);
      }
  };
  tbb::parallel_for(std::int32_t{0}, num_equations, [&](std::int32_t col) {
    std::int32_t count = 0;
    for_each_row(col, [&](std::int32_t) { ++count; });
    p.col_ptr[col + 1] = count;
  });
  for (std::int32_t j = 0; j < num_equations; ++j) p.col_ptr[j + 1] += p.col_ptr[j];
  p.row_idx.resize(static_cast<std::size_t>(p.col_ptr[num_equations]));
  layout.diagonal.resize(static_cast<std::size_t>(num_equations));
  tbb::parallel_for(std::int32_t{0}, num_equations, [&](std::int32_t col) {
    std::int32_t pos = p.col_ptr[col];
    for_each_row(col, [&](std::int32_t row) { p.row_idx[pos++] = row; });
    layout.diagonal[col] = p.col_ptr[col + 1] - 1;  // the diagonal is the last row of its column
  });
  // Rows a node's columns hold before each neighbour's: the neighbours below the node hold
  // their free dofs in both of its columns, in neighbour order.
  std::vector<std::int32_t>& rows_before = layout.neighbours.rows_before;
  rows_before.resize(neighbour.size());
  tbb::parallel_for(tbb::blocked_range<std::int32_t>(0, num_nodes, 1024), [&](auto range) {
    for (std::int32_t n = range.begin(); n != range.end(); ++n) {
      std::int32_t count = 0;
      for (std::int32_t q = neighbour_offset[n]; q < neighbour_offset[n + 1]; ++q) {
        rows_before[q] = count;
        const std::int32_t m = neighbour[q];
        count += (equation[2 * m] >= 0) + (equation[2 * m + 1] >= 0);
      }
    }
  });
  return layout;
}

void build_scatter_map(std::span<const std::int32_t> conn, std::span<const std::int32_t> equation,
                       StiffnessLayout& layout) {
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  const SparsityPattern& p = layout.pattern;
  const NodeNeighbours& graph = layout.neighbours;
  // Entry (row dof of node m, column dof of node n), m <= n in dof order, sits in the column at
  // the rows node n's neighbours before m hold, plus m's x row if the row is m's y: found with
  // one search of m among n's few neighbours per node pair instead of one per entry.
  auto position = [&](std::int32_t rows_before_m, std::int32_t m, int cm, std::int32_t col) {
    const std::int32_t skip = cm == 1 && equation[2 * m] >= 0 ? 1 : 0;
    return p.col_ptr[col] + rows_before_m + skip;
  };
  auto rows_before = [&](std::int32_t m, std::int32_t n) {
    // A count rather than a binary search: a node has about 7 neighbours, and a branch-free
    // count does not mispredict.
    std::int32_t q = graph.offset[n];
    for (std::int32_t k = graph.offset[n]; k < graph.offset[n + 1]; ++k) q += graph.node[k] < m;
    return graph.rows_before[q];
  };
  layout.scatter.resize(static_cast<std::size_t>(num_elements) * kElementUpperEntries);
  tbb::parallel_for(tbb::blocked_range<std::int32_t>(0, num_elements, 1024), [&](auto range) {
    for (std::int32_t e = range.begin(); e != range.end(); ++e) {
      const std::int32_t* node = &conn[3 * static_cast<std::size_t>(e)];
      // below[i][j]: rows node j's columns hold before node i's, for node i <= node j.
      std::int32_t below[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (node[i] <= node[j]) below[i][j] = rows_before(node[i], node[j]);
      std::int32_t* out = &layout.scatter[static_cast<std::size_t>(e) * kElementUpperEntries];
      for (int a = 0; a < 6; ++a)
        for (int b = a; b < 6; ++b) {
          int ia = a / 2, ca = a % 2, ib = b / 2, cb = b % 2;
          const std::int32_t ea = equation[2 * node[ia] + ca], eb = equation[2 * node[ib] + cb];
          if (ea < 0 || eb < 0) {
            *out++ = -1;
            continue;
          }
          if (ea > eb) {  // the row is b's dof
            std::swap(ia, ib);
            std::swap(ca, cb);
          }
          *out++ = position(below[ia][ib], node[ia], ca, std::max(ea, eb));
        }
    }
  });
  layout.neighbours = {};
}

StiffnessLayout build_stiffness_layout(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                                       std::span<const std::int32_t> equation) {
  StiffnessLayout layout = build_sparsity_pattern(conn, num_nodes, equation);
  build_scatter_map(conn, equation, layout);
  return layout;
}

}  // namespace rockdd

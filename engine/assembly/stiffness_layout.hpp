#pragma once
// Symbolic side of assembly: the sparsity pattern over free equations, computed once per
// topology, and the scatter map that sends each element entry to its nonzero.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/assembly/sparsity_pattern.hpp"
#include "kernels/cst.hpp"

namespace rockdd {

/// Entries of the upper triangle of a 6x6 element matrix, (a, b) with a <= b, row-major.
inline constexpr int kElementUpperEntries = kernels::kUpperEntries;

/// The node graph a pattern was built from, kept until the scatter map is made:
/// node[offset[n] .. offset[n + 1]) are the nodes sharing an element with n (n included),
/// ascending, and rows_before[q] is how many rows of node n's columns the neighbours before
/// node[q] hold (meaningful up to n itself, the upper triangle's part).
struct NodeNeighbours {
  std::vector<std::int32_t> offset, node, rows_before;
};

/// Pattern, scatter map and diagonal positions of the global stiffness.
struct StiffnessLayout {
  SparsityPattern pattern;
  std::vector<std::int32_t> scatter;   // 21 per element; value index or -1
  std::vector<std::int32_t> diagonal;  // per equation: value index of (i, i)
  NodeNeighbours neighbours;           // between the two halves only; emptied by the second
};

/// Builds the layout for elements `conn` over `num_nodes` nodes, where `equation[dof]` is the
/// equation number of each dof (2 per node) or -1 for a prescribed dof.
StiffnessLayout build_stiffness_layout(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                                       std::span<const std::int32_t> equation);

/// The first half of build_stiffness_layout: the pattern and the diagonal positions, scatter
/// map left empty (what CHOLMOD's analysis needs, so that it can run beside the second half).
StiffnessLayout build_sparsity_pattern(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                                       std::span<const std::int32_t> equation);

/// The second half: fills `layout.scatter` for elements `conn` from its pattern and node
/// graph (which it then frees). Needs equation numbers that increase with the dof index.
void build_scatter_map(std::span<const std::int32_t> conn, std::span<const std::int32_t> equation,
                       StiffnessLayout& layout);

}  // namespace rockdd

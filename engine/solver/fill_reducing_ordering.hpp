#pragma once
// Fill-reducing orderings of a symmetric pattern computed on its node graph rather than its
// dof graph. The two dofs of a mesh node have the same neighbours, so the equations split
// into groups with identical columns; ordering the quotient graph of the groups (half the
// vertices, a quarter of the edges of the dof graph in 2D) and keeping each group's
// equations together gives the same fill as ordering the dof graph, for much less work.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "engine/assembly/sparsity_pattern.hpp"

namespace rockdd {

/// How CholmodSolver::analyze orders the equations.
enum class FillOrdering {
  cholmod,         // CHOLMOD's own strategy on the dof graph: AMD, and METIS when AMD fills badly
  node_metis,      // METIS nested dissection (METIS_NodeND) of the node graph
  node_amd,        // AMD of the node graph
  node,            // cholmod_amd, then the dissections below where they may pay (OrderingEffort)
  cholmod_amd,     // CHOLMOD's AMD of the dof graph alone
  node_geometric,  // nested dissection of the node graph by the nodes' coordinates, then CAMD
};

/// What a fill-reducing ordering may cost. A system factorized once tries a nested dissection
/// only where AMD fills badly (CHOLMOD's test), and then the quick one by coordinates alone;
/// one factorized many times tries that one wherever AMD's factor is costly, and METIS's where
/// AMD fills badly. Each keeps the smallest factor.
enum class OrderingEffort { quick, thorough };

std::string_view fill_ordering_name(FillOrdering ordering);
/// The ordering fill_ordering_name() calls `name`; nullopt for any other text.
std::optional<FillOrdering> fill_ordering_from_name(std::string_view name);

/// The equations cut into runs of consecutive equations whose columns of the full symmetric
/// pattern (diagonal included) are identical: run g is [start[g], start[g + 1]). In a
/// stiffness layout each run is the free dofs of one node.
std::vector<std::int32_t> equation_groups(const SparsityPattern& pattern);

/// x and y of each equation's node (two values an equation), from the nodes' positions
/// `node_xy` (two values a node) and the equation of each dof (-1 where prescribed).
std::vector<double> equation_positions(std::span<const double> node_xy,
                                       std::span<const std::int32_t> equation,
                                       std::int32_t num_equations);

/// The elimination order of the equations by AMD, METIS or the coordinates' nested
/// dissection (FillOrdering::node_amd, node_metis, node_geometric) of the node graph: perm[k]
/// is the equation eliminated k-th, the equations of each group of equation_groups()
/// consecutive and in increasing order. `equation_xy` (x and y of each equation's node, two
/// values an equation) is read by node_geometric only, which needs it.
/// Deterministic: METIS runs with its fixed default seed.
std::vector<std::int32_t> node_graph_ordering(const SparsityPattern& pattern, FillOrdering ordering,
                                              std::span<const double> equation_xy = {});

}  // namespace rockdd

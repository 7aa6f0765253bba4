#include "engine/solver/fill_reducing_ordering.hpp"

#include "engine/solver/coordinate_dissection.hpp"

#include <amd.h>
#include <metis.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rockdd {
namespace {

static_assert(sizeof(idx_t) == sizeof(std::int32_t), "METIS built with 64-bit indices");

/// Both triangles of a symmetric pattern given by its upper triangle, diagonal included,
/// as compressed rows. Filling column by column in increasing order leaves every row sorted:
/// row c gets its entries r < c, then c, while column c is read, and its entries above c
/// later, in the order of their columns.
struct Adjacency {
  std::vector<std::int32_t> offset, index;
  std::int32_t begin(std::int32_t i) const { return offset[i]; }
  std::int32_t end(std::int32_t i) const { return offset[i + 1]; }
};

Adjacency closed_adjacency(const SparsityPattern& p) {
  Adjacency a;
  a.offset.assign(static_cast<std::size_t>(p.n) + 1, 0);
  for (std::int32_t c = 0; c < p.n; ++c)
    for (std::int32_t q = p.col_ptr[c]; q < p.col_ptr[c + 1]; ++q) {
      const std::int32_t r = p.row_idx[q];
      ++a.offset[c + 1];
      if (r != c) ++a.offset[r + 1];
    }
  for (std::int32_t i = 0; i < p.n; ++i) a.offset[i + 1] += a.offset[i];
  a.index.resize(static_cast<std::size_t>(a.offset[p.n]));
  std::vector<std::int32_t> next(a.offset.begin(), a.offset.end() - 1);
  for (std::int32_t c = 0; c < p.n; ++c)
    for (std::int32_t q = p.col_ptr[c]; q < p.col_ptr[c + 1]; ++q) {
      const std::int32_t r = p.row_idx[q];
      a.index[next[c]++] = r;
      if (r != c) a.index[next[r]++] = c;
    }
  return a;
}

std::vector<std::int32_t> groups_of(const Adjacency& a, std::int32_t n) {
  std::vector<std::int32_t> start{0};
  for (std::int32_t i = 1; i < n; ++i) {
    const bool same = std::equal(a.index.begin() + a.begin(i - 1), a.index.begin() + a.end(i - 1),
                                 a.index.begin() + a.begin(i), a.index.begin() + a.end(i));
    if (!same) start.push_back(i);
  }
  if (n > 0) start.push_back(n);
  return start;
}

}  // namespace

std::string_view fill_ordering_name(FillOrdering ordering) {
  switch (ordering) {
    case FillOrdering::cholmod:
      return "cholmod";
    case FillOrdering::node_metis:
      return "node_metis";
    case FillOrdering::node_amd:
      return "node_amd";
    case FillOrdering::node:
      return "node";
    case FillOrdering::cholmod_amd:
      return "cholmod_amd";
    case FillOrdering::node_geometric:
      return "node_geometric";
  }
  return "unknown";
}

std::optional<FillOrdering> fill_ordering_from_name(std::string_view name) {
  for (const FillOrdering o :
       {FillOrdering::cholmod, FillOrdering::node_metis, FillOrdering::node_amd, FillOrdering::node,
        FillOrdering::cholmod_amd, FillOrdering::node_geometric})
    if (fill_ordering_name(o) == name) return o;
  return std::nullopt;
}

std::vector<std::int32_t> equation_groups(const SparsityPattern& pattern) {
  return groups_of(closed_adjacency(pattern), pattern.n);
}

std::vector<double> equation_positions(std::span<const double> node_xy,
                                       std::span<const std::int32_t> equation,
                                       std::int32_t num_equations) {
  std::vector<double> xy(2 * static_cast<std::size_t>(num_equations));
  for (std::size_t d = 0; d < equation.size(); ++d)
    if (const std::int32_t eq = equation[d]; eq >= 0) {
      xy[2 * static_cast<std::size_t>(eq)] = node_xy[d & ~std::size_t{1}];
      xy[2 * static_cast<std::size_t>(eq) + 1] = node_xy[d | 1];
    }
  return xy;
}

std::vector<std::int32_t> node_graph_ordering(const SparsityPattern& pattern, FillOrdering ordering,
                                              std::span<const double> equation_xy) {
  if (ordering != FillOrdering::node_metis && ordering != FillOrdering::node_amd &&
      ordering != FillOrdering::node_geometric)
    throw std::invalid_argument("node_graph_ordering: AMD, METIS or coordinates only, not " +
                                std::string(fill_ordering_name(ordering)));
  if (ordering == FillOrdering::node_geometric &&
      equation_xy.size() != 2 * static_cast<std::size_t>(pattern.n))
    throw std::invalid_argument("node_graph_ordering: " + std::to_string(equation_xy.size()) +
                                " coordinates for " + std::to_string(pattern.n) +
                                " equations (two each)");
  const Adjacency dofs = closed_adjacency(pattern);
  const std::vector<std::int32_t> start = groups_of(dofs, pattern.n);
  const auto num_groups = static_cast<std::int32_t>(start.size()) - 1;

  // The quotient graph: group g is adjacent to the groups of its first equation's
  // neighbours. Rows are sorted and groups are runs of equations, so the mapped neighbours
  // come sorted and a repeat is always the previous one. No self loops (METIS wants none).
  std::vector<std::int32_t> group_of(static_cast<std::size_t>(pattern.n));
  for (std::int32_t g = 0; g < num_groups; ++g)
    std::fill(group_of.begin() + start[g], group_of.begin() + start[g + 1], g);
  std::vector<std::int32_t> xadj{0}, adjncy, weight(static_cast<std::size_t>(num_groups));
  adjncy.reserve(dofs.index.size() / 4 + static_cast<std::size_t>(num_groups));
  for (std::int32_t g = 0; g < num_groups; ++g) {
    const std::int32_t i = start[g];
    for (std::int32_t q = dofs.begin(i); q < dofs.end(i); ++q) {
      const std::int32_t h = group_of[dofs.index[q]];
      if (h != g && (adjncy.size() == static_cast<std::size_t>(xadj.back()) || adjncy.back() != h))
        adjncy.push_back(h);
    }
    xadj.push_back(static_cast<std::int32_t>(adjncy.size()));
    weight[g] = start[g + 1] - start[g];
  }

  std::vector<std::int32_t> order(static_cast<std::size_t>(num_groups));
  if (adjncy.empty()) {
    for (std::int32_t g = 0; g < num_groups; ++g) order[g] = g;  // nothing to reduce
  } else if (ordering == FillOrdering::node_geometric) {
    std::vector<double> x(static_cast<std::size_t>(num_groups)), y(x.size());
    for (std::int32_t g = 0; g < num_groups; ++g) {
      x[g] = equation_xy[2 * static_cast<std::size_t>(start[g])];
      y[g] = equation_xy[2 * static_cast<std::size_t>(start[g]) + 1];
    }
    order = coordinate_dissection_order(GraphView{xadj, adjncy}, x, y);
  } else if (ordering == FillOrdering::node_metis) {
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    std::vector<idx_t> inverse(static_cast<std::size_t>(num_groups));
    idx_t nvtxs = num_groups;
    // The weights count each node's free dofs, so that separators are balanced in equations.
    const int status = METIS_NodeND(&nvtxs, xadj.data(), adjncy.data(), weight.data(), options,
                                    order.data(), inverse.data());
    if (status != METIS_OK)
      throw std::runtime_error("METIS_NodeND failed (status " + std::to_string(status) + ")");
  } else {
    const int status =
        amd_order(num_groups, xadj.data(), adjncy.data(), order.data(), nullptr, nullptr);
    if (status != AMD_OK)
      throw std::runtime_error("AMD failed (status " + std::to_string(status) + ")");
  }

  std::vector<std::int32_t> perm;
  perm.reserve(static_cast<std::size_t>(pattern.n));
  for (const std::int32_t g : order)
    for (std::int32_t e = start[g]; e < start[g + 1]; ++e) perm.push_back(e);
  return perm;
}

}  // namespace rockdd

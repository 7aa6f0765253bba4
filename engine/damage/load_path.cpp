#include "engine/damage/load_path.hpp"

#include <cstdint>
#include <vector>

#include "engine/common/disjoint_sets.hpp"

namespace rockdd {

namespace {

/// What a node's prescribed dofs do, one bit each: x moves, y moves, x fixed, y fixed.
std::uint8_t boundary_role(const BoundaryConditions& bc, std::size_t node) {
  std::uint8_t role = 0;
  for (std::size_t c = 0; c < 2; ++c) {
    const std::size_t d = 2 * node + c;
    if (!bc.prescribed[d]) continue;
    role |= bc.velocity[d] != 0.0 ? std::uint8_t(1u << c) : std::uint8_t(4u << c);
  }
  return role;
}

/// A role in which some direction both moves and is held.
bool drives_and_holds(std::uint8_t role) {
  return ((role & 3u) & (role >> 2)) != 0;
}

}  // namespace

bool has_load_path_boundaries(const BoundaryConditions& bc) {
  std::uint8_t role = 0;
  for (std::size_t n = 0; 2 * n < bc.prescribed.size(); ++n) role |= boundary_role(bc, n);
  return drives_and_holds(role);
}

bool joins_moving_and_fixed_boundaries(const Model& model, const BoundaryConditions& bc,
                                       std::span<const Contact> contacts) {
  const auto num_nodes = static_cast<std::size_t>(model.num_nodes());
  DisjointSets parts(num_nodes);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (model.damage[e] >= 1.0) continue;
    const std::int32_t* corner = &model.conn[3 * static_cast<std::size_t>(e)];
    parts.join(corner[0], corner[1]);
    parts.join(corner[0], corner[2]);
  }
  for (const Contact& c : contacts)
    if (c.state != ContactState::open) {
      parts.join(c.vertex, c.a);
      parts.join(c.vertex, c.b);
    }
  std::vector<std::uint8_t> role(num_nodes, 0);
  for (std::size_t n = 0; n < num_nodes; ++n) {
    const std::uint8_t own = boundary_role(bc, n);
    if (own == 0) continue;
    std::uint8_t& joined = role[static_cast<std::size_t>(parts.find(static_cast<std::int32_t>(n)))];
    joined |= own;
    if (drives_and_holds(joined)) return true;
  }
  return false;
}

}  // namespace rockdd

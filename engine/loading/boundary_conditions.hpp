#pragma once
// Prescribed dofs (fixed or moving at an imposed velocity) and the equation numbering of
// the free dofs that the stiffness is assembled over.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Per-dof constraint data (2 dofs per node).
struct BoundaryConditions {
  std::vector<std::uint8_t> prescribed;  // 1 when the dof is fixed or moving
  std::vector<double> velocity;          // imposed velocity (0 for fixed dofs)
  std::vector<std::int32_t> equation;    // equation of a free dof, -1 if prescribed
  std::int32_t num_equations = 0;
};

/// Applies the scene's [[boundary]] entries in order (a later entry overrides an earlier one
/// on shared dofs) and numbers the free dofs in dof order.
BoundaryConditions build_boundary_conditions(const Scene& scene, const Model& model);

/// A block that the constraints leave free to move rigidly, and how.
struct FreeBlock {
  std::int32_t block = -1;
  std::int32_t elements = 0;
  std::string body;    // body of the block's first element
  std::string motion;  // "x translation", "y translation" or "rotation"
};

/// The first block of more than `min_elements - 1` elements that the prescribed dofs do not
/// hold against all three rigid-body modes, if any.
std::optional<FreeBlock> find_free_block(const Model& model, const BoundaryConditions& bc,
                                         std::int32_t min_elements = 1);

/// Per block, 1 when the prescribed dofs do not hold all three of its rigid-body modes.
std::vector<std::uint8_t> unrestrained_blocks(const Model& model, const BoundaryConditions& bc);

/// A node's membership of a group of nodes.
struct GroupNode {
  std::int32_t group = 0;
  std::int32_t node = 0;
};

/// The same for any groups of nodes (`members`: (group, node) pairs, each once; a node may be
/// in several groups): per group in [0, num_groups), 1 when the prescribed dofs of its nodes do
/// not hold all three of its rigid-body modes.
std::vector<std::uint8_t> unrestrained_groups(const Model& model, const BoundaryConditions& bc,
                                              std::span<const GroupNode> members,
                                              std::int32_t num_groups);

/// A static analysis needs every block held against its three rigid-body modes; throws
/// InputError naming the first block that is not (and its body).
void check_static_restraint(const Scene& scene, const Model& model, const BoundaryConditions& bc);

/// The constraints' force on the body at a dof: at a prescribed one, what the body's own
/// forces leave unbalanced there (f_int + f_contact + restraint - f_ext); elsewhere 0.
inline double constraint_force(bool prescribed, double f_int, double f_contact, double restraint,
                               double f_ext) {
  return prescribed ? f_int + f_contact + restraint - f_ext : 0.0;
}

}  // namespace rockdd

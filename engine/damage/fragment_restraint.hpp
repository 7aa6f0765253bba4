#pragma once
// Fragments in steps without inertia (METHOD.md, loose fragments). A block that fracture cut
// loose and that no boundary holds has rigid-body modes that only its contacts restrain: a
// static step has no mass term, and a quasi-static step's 2 m / dt^2 is far too small to hold
// it (a lone element's corner in the compression scene: 2 x 1.25 g / (12.5 ms)^2 = 16 N/m,
// against 1e-6 x 50 GPa x 1 m / 3 = 1.7e4 N/m of spring), so K is singular or nearly so
// whenever those contacts are open. Each node of such a block gets a spring to where the step
// started, of a small fraction of the rock's stiffness (the force is the spring times the
// step's increment). It acts on every node, not only on the block's rigid modes, and also on
// blocks that closed contacts hold; docs/convergence.md measures what that still costs (the
// compression peak moves by up to 7 % at 0.1x the default).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/loading/boundary_conditions.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// Diagonal springs on the nodes of the blocks no boundary restrains.
class FragmentRestraint {
 public:
  FragmentRestraint() = default;
  /// Springs of `fraction` x E0 t / 3 per element corner on every node of a block whose three
  /// rigid-body modes the prescribed dofs do not all hold. Deterministic, in node order.
  FragmentRestraint(const Model& model, const BoundaryConditions& bc, double fraction);

  /// Adds the springs to the diagonal of K: `diagonal[eq]` is the value slot of equation eq.
  void add_stiffness(std::span<const std::int32_t> equation, std::span<const std::int32_t> diagonal,
                     std::span<double> values) const;
  /// force[d] = k du[d] on the restrained nodes, 0 elsewhere (2 per node).
  void forces(std::span<const double> du, std::span<double> force) const;
  /// Elastic energy of the springs at increment du (J): sum of k du^2 / 2.
  double energy(std::span<const double> du) const;

  std::size_t num_nodes() const { return nodes_.size(); }

 private:
  std::vector<std::int32_t> nodes_;
  std::vector<double> stiffness_;  // N/m, per restrained node
};

}  // namespace rockdd

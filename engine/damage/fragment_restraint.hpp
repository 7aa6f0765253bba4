#pragma once
// Fragments in steps without inertia (METHOD.md "Loose fragments"). A block that fracture cut
// loose and that no boundary holds has rigid-body modes that only its contacts restrain, and
// with no mass term K is singular whenever those contacts are open. Each node of such a block
// gets a spring to where the step started, of a small fraction of the rock's stiffness: it
// fixes the null space and, being that small, carries a negligible share of any load (the
// force is the spring times the step's increment). docs/convergence.md measures the strength
// against the fraction.
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

  std::size_t num_nodes() const { return nodes_.size(); }

 private:
  std::vector<std::int32_t> nodes_;
  std::vector<double> stiffness_;  // N/m, per restrained node
};

}  // namespace rockdd

#pragma once
// Fragments in steps without inertia (METHOD.md, loose fragments). A block that fracture cut
// loose and that no boundary holds has rigid-body modes that only its contacts restrain: a
// static step has no mass term, and a quasi-static step's 2 m / dt^2 is far too small to hold
// it (a lone element's corner in the compression scene: 2 x 1.25 g / (12.5 ms)^2 = 16 N/m,
// against 1e-6 x 50 GPa x 1 m / 3 = 1.7e4 N/m of spring), so K is singular or nearly so
// whenever those contacts are open. Each node of such a block gets a spring to where the step
// started, of a small fraction of the rock's stiffness (the force is the spring times the
// step's increment). It acts on every node, also on blocks that closed contacts hold (so that
// contacts can still move them); docs/convergence.md measures that the compression and disk
// peaks do not move with it at 0.1x and 10x. A part that a damage cascade cuts loose inside a
// step gets instead a statically determinate support on its free rigid modes only.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/loading/boundary_conditions.hpp"
#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// Diagonal springs on the nodes of the blocks no boundary restrains.
class FragmentRestraint {
 public:
  FragmentRestraint() = default;
  /// Springs of `fraction` x E0 t / 3 per element corner on every node of a part whose three
  /// rigid-body modes the prescribed dofs do not all hold. A part is what the elements that are
  /// not fully broken (w < 1) join: a detached block, or, inside a step's damage cascade, a
  /// piece that elements broken in that step (still attached, at the floor stiffness) cut
  /// loose; a node that only broken elements touch is a part alone. Deterministic.
  /// A part of a held block that broken elements cut loose inside the step instead gets a
  /// statically determinate support: springs of `support` x E0 t on as few of its dofs as hold
  /// its free rigid modes. `edges` is the edge adjacency of model.conn.
  FragmentRestraint(const Model& model, const EdgeAdjacency& edges, const BoundaryConditions& bc,
                    double fraction, double support = 1.0);
  /// The same, with the edge adjacency built here.
  FragmentRestraint(const Model& model, const BoundaryConditions& bc, double fraction,
                    double support = 1.0);

  /// The restrained dofs and the spring (N/m) on each: what K's diagonal gains.
  std::span<const std::int32_t> dofs() const { return dofs_; }
  std::span<const double> stiffness() const { return stiffness_; }
  /// force[d] = k du[d] on the restrained dofs, 0 elsewhere (2 per node).
  void forces(std::span<const double> du, std::span<double> force) const;
  /// Elastic energy of the springs at increment du (J): sum of k du^2 / 2.
  double energy(std::span<const double> du) const;

  /// Springs added since `before` (inside a step) start from the increment `du` they were
  /// added at, instead of from the step's start: they hold a part where the step has taken
  /// it. Springs `before` had keep its anchors.
  void anchor_new_springs(const FragmentRestraint& before, std::span<const double> du);
  /// Every spring starts from the increment du: the parts are held where they are now, not
  /// where the step started (Simulation::relax_restraint).
  void follow(std::span<const double> du);
  /// Every spring starts from the step's start again, as each step begins.
  void restart() { anchor_.clear(); }

  std::size_t num_dofs() const { return dofs_.size(); }
  /// Same dofs, springs and anchors.
  bool operator==(const FragmentRestraint& other) const = default;
  /// Whether both hold the same dofs with the same springs (anchors aside).
  bool same_springs(const FragmentRestraint& other) const {
    return dofs_ == other.dofs_ && stiffness_ == other.stiffness_;
  }

 private:
  std::vector<std::int32_t> dofs_;
  std::vector<double> stiffness_;  // N/m, per restrained dof
  std::vector<double> anchor_;     // increment each spring starts from (empty: all 0)
  double anchor(std::size_t i) const { return anchor_.empty() ? 0.0 : anchor_[i]; }
};

}  // namespace rockdd

#pragma once
// The contact stage of a step (METHOD.md "Contact"): vertex-edge contacts between blocks,
// penalty springs (normal kn, shear ks) with Coulomb friction, and the state bookkeeping of
// the open-close iteration. Built only for scenes with [[joint]] entries. Validated against
// the inclined plane with and without friction and a block braked by friction
// (tests/test_contact.cpp). Joints with cohesion or tensile strength bond the faces that
// touch at the start until the bond is sheared or pulled apart.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/assembly/low_rank_terms.hpp"
#include "engine/assembly/slot_matrices.hpp"
#include "engine/contact/contact.hpp"
#include "engine/contact/contact_detection.hpp"
#include "engine/contact/contact_rules.hpp"
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// The force scale of a state without inertia (N), below which contact forces need not be
/// resolved: the largest force an element edge carries (|sigma| sqrt(2 A) t, from
/// model.stress), load (`f_ext`) or reaction (`reaction`) on a node.
double contact_force_scale(const Model& model, std::span<const double> reaction,
                           std::span<const double> f_ext);

/// Contact detection, springs and states over a step.
class ContactStage {
 public:
  /// Boundary and rules from the model and the scene's joints; defaults for kn, ks; the
  /// sliding springs and forgiven overlaps of steps without inertia unless `analysis` is
  /// dynamic.
  /// With Newmark's scheme (`integrator` in a dynamic `analysis`) the solve takes each
  /// contact's normal force as its mean over the step (kernels::mean_normal_force), so that
  /// a spring that opens or closes within a step makes no energy.
  ContactStage(const Scene& scene, const Model& model, Analysis analysis, Integrator integrator);
  /// The same, with the edge adjacency of model.conn that the caller keeps.
  ContactStage(const Scene& scene, const Model& model, const EdgeAdjacency& edges,
               Analysis analysis, Integrator integrator);

  /// The sliding springs and forgiven overlaps of steps without inertia, or neither with it
  /// (a run that goes on with inertia: fracture.snap_back = "dynamic"), and the mean normal
  /// force with Newmark's scheme.
  void set_analysis(Analysis analysis, Integrator integrator);

  /// Finds the contacts at `positions`; the pairs that persist from the committed contacts
  /// `committed` (sorted by vertex and edge) keep their state. Returns true when the set of
  /// (vertex, a, b) triples changed (the pattern must be rebuilt).
  bool detect(std::span<const double> positions, std::span<const Contact> committed);
  /// Node triples (vertex, a, b) of the contacts, appended to the element connectivity
  /// when the stiffness layout is built.
  std::vector<std::int32_t> triples() const;
  /// Adds the forces of the closed contacts' springs at `positions` to `force` (2 per node).
  void add_spring_forces(std::span<const double> positions, std::span<double> force) const;
  /// The contact forces the solve takes at `positions`, added to `force`: add_spring_forces'
  /// without inertia and with DDA's scheme. With Newmark's, the sum of the step's start and
  /// end forces, which its equation holds, taken so that contacts make no energy: twice the
  /// normal force's mean over the step (kernels::mean_normal_force, on its tangent), of every
  /// contact whose spring was closed at the start or is now; the shear of a contact locked
  /// over the whole step at its start and end, and otherwise twice its end force.
  void add_solve_forces(std::span<const double> positions, std::span<double> force) const;
  /// Whether the solve takes each normal force as its mean over the step (Newmark).
  bool energy_consistent() const { return energy_consistent_; }
  /// The springs of the closed contacts as matrices for K: contact c at slot `first_slot + c`
  /// of the layout (its triple follows the elements').
  const SlotMatrices& spring_matrices(std::int32_t first_slot);
  /// Updates the states from the solved `positions`; returns how many changed (at least 1
  /// while a contact is deeper than penetration_limit: a runaway never settles), and the
  /// largest penetration. Gaps and slips are the step's linearised ones, the same the solve
  /// used: the exact gap at the end of a step differs from it by O(du^2 / L), which near zero
  /// force is enough to flip a contact back and forth forever.
  /// `tolerance_scale` widens the force tolerance (1 = force_tolerance of the largest contact
  /// force) for iterations that chatter. With `settle`, contacts that have already swung
  /// between two answers in this attempt take their last answer without counting as a change
  /// (a shear swing keeps the state the solve implies; an open-close swing is left open).
  int update_states(std::span<const double> positions, double tolerance_scale, bool settle,
                    double& largest_penetration);
  /// Commits a converged step ending at `positions`: the elastic slip of locked contacts
  /// accumulates, other contacts forget theirs; contacts() are then the committed contacts.
  /// Adds friction's work over the slip the anchors followed in the step to `friction_work`
  /// (J per the thickness), contact by contact; returns the springs' elastic energy (J).
  double commit(std::span<const double> positions, double& friction_work);
  /// The contacts of the step being solved (after commit(): as committed).
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The step's contacts set back to an earlier copy of contacts() (a solve taken back).
  void restore_contacts(std::vector<Contact> contacts) { contacts_ = std::move(contacts); }
  /// Adds to `force` (2 per node) the forces of the closed contacts at `positions` after
  /// commit(): a locked contact's shear is its committed elastic slip, which add_spring_forces
  /// would count twice with the step's slip.
  void add_committed_forces(std::span<const double> positions, std::span<double> force) const;

  /// Whether a step has been committed (contacts that form after it are not bonded), and
  /// setting it back for a commit that was taken back.
  bool committed_before() const { return started_; }
  void set_committed_before(bool committed) { started_ = committed; }

  /// Sets `node_mask[n]` to 1 for every node (vertex or edge end) of a closed contact.
  void mark_touching_nodes(std::span<std::uint8_t> node_mask) const;

  /// The springs of all contacts, in order (to compare before and after an update).
  std::vector<ContactSprings> springs() const;
  /// The springs that differ between `before` (from springs()) and the current ones, as
  /// columns sqrt(k) g over the equations `equation` (per dof, -1 when prescribed): a normal
  /// spring kn g g^T unless open, a shear spring k t t^T (ks locked, the contact's
  /// sliding stiffness sliding).
  /// The columns of the springs added, and of those removed.
  struct SpringChanges {
    LowRankTerms added, removed;
  };
  const SpringChanges& spring_changes(std::span<const ContactSprings> before,
                                      std::span<const std::int32_t> equation);

  /// After fracture rebuilt the blocks: takes over the committed contacts `committed` of the
  /// stage `old`, where their vertex and edge still exist (node ids survive a split), with
  /// their edges renumbered in `committed`.
  void carry_contacts_from(const ContactStage& old, std::vector<Contact>& committed);

  /// Elastic energy the closed contacts' springs would hold at `positions`, in their current
  /// states (J; as spring_energy() counts it at a commit).
  double spring_energy_at(std::span<const double> positions) const;
  /// Work of friction of the sliding contacts between two iterates of a step (J): the friction
  /// force times the slip from `from` to `to`.
  double friction_work_between(std::span<const double> from, std::span<const double> to) const;

  /// Contacts whose shear force kept swinging and settled on their last answer (cumulative).
  long shear_swings_settled() const { return shear_swings_settled_; }
  /// Contacts that kept opening and closing and were left open (cumulative).
  long normal_swings_settled() const { return normal_swings_settled_; }

  const ContactParameters& parameters() const { return rules_.parameters; }
  /// Forces below force_tolerance x this scale (N) settle: the forces that flow through
  /// the model's elements, so that a fragment carrying next to nothing is not held to a
  /// tolerance far below what matters for the rest.
  void set_force_scale(double scale) { force_scale_ = scale; }

  /// The normal stiffness contact c adds to K: kn closed, or with Newmark's scheme the
  /// tangent of its mean normal force.
  double normal_stiffness(const Contact& c) const;
  /// The shear stiffness contact c adds to K: ks locked, its sliding spring sliding; with
  /// Newmark's scheme twice that unless locked over the whole step (add_solve_forces).
  double shear_stiffness(const Contact& c) const {
    const double k = c.state == ContactState::locked    ? rules_.parameters.shear_stiffness
                     : c.state == ContactState::sliding ? c.slide_stiffness
                                                        : 0.0;
    return energy_consistent_ && !(c.state == ContactState::locked && c.locked_at_start) ? 2.0 * k
                                                                                         : k;
  }
  std::size_t size() const { return contacts_.size(); }

 private:
  /// The shear force a closed contact's solve assumed and the one its result implies.
  struct ShearUpdate {
    double assumed = 0.0, implied = 0.0;
    bool bond_broke = false;
  };
  /// Coulomb's law with inertia: friction is a load from the last normal force.
  ShearUpdate update_shear_with_inertia(Contact& c, double gap, double slip, double tolerance);
  /// Coulomb's law without inertia: a sliding contact keeps the spring sliding_stiffness.
  ShearUpdate update_shear_without_inertia(Contact& c, double gap, double slip, double tolerance);
  /// Takes contact c's mean normal force at end gap `gap` as its new line; returns whether the
  /// line the solve used was off it by more than `tolerance` (N).
  bool follow_mean_normal_force(Contact& c, double gap, double tolerance) const;
  /// The normal force friction uses at gap `gap` (lagged once the shear has swung).
  double friction_normal_force(Contact& c, double gap) const;
  /// Friction (and cohesion, while bonded) under `normal_force`; a bond sheared past it by
  /// the elastic force breaks for good.
  double shear_capacity(Contact& c, double normal_force, double elastic_force, double tolerance,
                        bool& bond_broke) const;

  BlockBoundary boundary_;
  ContactRulebook rules_;
  std::vector<Contact> contacts_;  // of the step being solved
  long shear_swings_settled_ = 0, normal_swings_settled_ = 0;
  double force_scale_ = 0.0;

  SlotMatrices spring_matrices_;  // scratch of spring_matrices()
  SpringChanges spring_changes_;  // scratch of spring_changes()
  bool started_ = false;  // a step has been committed: contacts that form now are not bonded
  bool energy_consistent_ = false;  // Newmark: the solve takes mean normal forces
};

}  // namespace rockdd

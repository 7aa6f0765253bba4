#pragma once
// The contact stage of a step (METHOD.md "Contact"): vertex-edge contacts between blocks,
// penalty springs (normal kn, shear ks) with Coulomb friction, and the state bookkeeping of
// the open-close iteration. Built only for scenes with [[joint]] entries. Frictionless
// contact is validated (tests/test_contact.cpp); the friction branch is written but does not
// yet reproduce the inclined-plane answers, so supported_features keeps friction off.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/assembly/stiffness_layout.hpp"
#include "engine/contact/contact_detection.hpp"
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Open: no spring. Sliding: normal spring, friction force. Locked: normal and shear springs.
enum class ContactState : std::uint8_t { open, sliding, locked };

/// One vertex-edge contact and what it remembers across iterations and steps.
struct Contact {
  std::int32_t vertex = -1, a = -1, b = -1;  // nodes: vertex p, edge a->b
  std::int32_t edge = -1;                    // boundary edge index
  ContactState state = ContactState::open;   // state assumed in the current solve
  double shear_spring = 0.0;                 // committed elastic slip of a locked contact (m)
  double slip_sign = 0.0;                    // direction of sliding, for the friction force
  double friction = 0.0, cohesion = 0.0;     // tan(phi), c (Pa) of the joint
};

/// Joint parameters that contacts use, derived from the scene.
struct ContactParameters {
  double normal_stiffness = 0.0;  // kn, N/m
  double shear_stiffness = 0.0;   // ks, N/m
  double reach = 0.0;             // search distance for candidates, m
  double gap_tolerance = 0.0;     // an opening below it does not hold the iteration back
  double thickness = 1.0;
};

/// Contact detection, springs and states over a step.
class ContactStage {
 public:
  /// Boundary and rules from the model and the scene's joints; defaults for kn, ks.
  ContactStage(const Scene& scene, const Model& model);

  /// Finds the contacts at `positions`; keeps the state of pairs that persist. Returns true
  /// when the set of (vertex, a, b) triples changed (the pattern must be rebuilt).
  bool detect(std::span<const double> positions);
  /// Node triples (vertex, a, b) of the contacts, appended to the element connectivity
  /// when the stiffness layout is built.
  std::vector<std::int32_t> triples() const;
  /// Adds the springs of closed contacts to K (layout entries of contact c are those of
  /// element `first_slot + c`) and their forces at `positions` to `force` (2 per node).
  void add_springs(std::span<const double> positions, const StiffnessLayout& layout,
                   std::int32_t first_slot, std::span<double> values,
                   std::span<double> force) const;
  /// Updates the states from the solved `positions`; returns how many changed, and the
  /// largest penetration.
  int update_states(std::span<const double> positions, double& largest_penetration);
  /// Commits a converged step ending at `positions`: the elastic slip of locked contacts
  /// accumulates, other contacts forget theirs.
  void commit(std::span<const double> positions);

  const ContactParameters& parameters() const { return parameters_; }
  std::size_t size() const { return contacts_.size(); }

 private:
  ContactParameters parameters_;
  BlockBoundary boundary_;
  ContactRules rules_;
  std::vector<Contact> contacts_;
  std::vector<double> joint_friction_, joint_cohesion_;  // per body pair
  std::vector<double> step_start_;                       // positions at the start of the step
  /// Tangential slip of contact c since the start of the step, along the slip gradient t.
  double step_slip(const double t[6], const Contact& c, std::span<const double> positions) const;
};

}  // namespace rockdd

#pragma once
// The state every step attempt starts from: what the last committed step left, after its
// fracture. The commit is the one place that writes it, and an attempt restores the model's
// working fields from it, so a rejected attempt leaves nothing behind. (The displacement and
// velocity are the model's own: only the commit writes them.)
#include <optional>
#include <span>
#include <vector>

#include "engine/contact/contact.hpp"
#include "engine/damage/first_damage.hpp"
#include "engine/damage/fragment_restraint.hpp"
#include "engine/damage/run_event.hpp"
#include "engine/state/energy_account.hpp"

namespace rockdd {

/// Damage, stresses, forces, contacts, restraint and energy at the last commit.
struct CommittedState {
  // Per element (strain and stress 3 each): at the committed displacement.
  std::vector<double> damage, strain, stress;
  // Per element (6 each): its nodal force at the committed displacement, from which the next
  // attempt's start recomputes only the elements the prescribed increment moves.
  std::vector<double> element_force;
  // Per dof: the loads and the constraints' force, and Newmark's acceleration (0 without
  // inertia).
  std::vector<double> f_ext, reaction, acceleration;
  // Per dof: what the free dofs are out of balance by (f_ext - f_int - f_contact - restraint;
  // 0 on prescribed ones). Without inertia a step ends balanced against its mass term, not
  // at rest, and a load applied at once starts out of balance: the next step's loss.
  std::vector<double> residual;
  // Per dof: the contact springs' force at the commit (as f_int: the body pushes them). With
  // DDA's scheme those its last solve had, with Newmark's those `acceleration` balances.
  std::vector<double> contact_force;
  double load_factor = 0.0;
  // Elements' and contact springs' elastic energy: where a step that starts out of balance
  // measures its snap-back from.
  double stored_energy = 0.0;
  double contact_spring_energy = 0.0;
  // No equilibrium: the last damage pass dropped moduli without a re-solve, or nodes split.
  bool out_of_balance = false;
  std::vector<Contact> contacts;  // sorted by (vertex, edge)
  FragmentRestraint restraint;
  EnergyAccount energy;
  std::optional<FirstDamage> first_damage;
  std::vector<RunEvent> events;  // in the order they happened, each name once

  /// Whether the run has had event `name`.
  bool has_event(const std::string& name) const;

  /// Zeroed per-dof arrays for `num_dofs` dofs.
  void resize(std::size_t num_dofs);
  /// After nodes split (detach_damaged_elements): each new node takes its origin's values.
  void follow_split_nodes(std::span<const std::int32_t> node_origin);
};

}  // namespace rockdd

#pragma once
// The trial state of the step being attempted: the arrays Simulation's step loop reads and
// writes between the stages, and what the attempt found. Each attempt starts it afresh from
// the committed state (committed_state.hpp); the commit takes what it keeps from here.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/damage/first_damage.hpp"
#include "engine/damage/run_event.hpp"
#include "engine/state/energy_account.hpp"

namespace rockdd {

/// Per-dof arrays (2 per node) of the step being attempted, and the attempt's own findings.
struct StepState {
  std::vector<double> f_int, f_ext;            // internal force at the trial (after the commit: the
                                               // committed) displacement; loads
  std::vector<double> reaction;                // constraint forces at the step's end
  std::vector<double> reaction_first;          // constraint forces after the step's first solve,
                                               // before its damage cascade
  std::vector<double> u_trial;                 // committed u plus the prescribed increment
  std::vector<double> du;                      // the step's displacement increment
  std::vector<double> f_contact;               // contact spring forces at the trial state
  std::vector<double> contact_force_solved;    // with DDA's inertia: the contact forces the
                                               // last solve had, before its update switched any
  std::vector<double> contact_force_sum;       // with Newmark's: the contact forces the solve
                                               // took at the step's end (start plus end forces)
  std::vector<double> positions;               // scratch: X + u for geometry queries
  std::vector<double> damage_force;            // f_int at the step's result, for damage checks
  std::vector<double> restraint_force;         // fragment restraint's force on the increment
  std::vector<double> positions_settled;       // X + u + du where the last damage pass dropped
                                               // the moduli (the snap-back's start)
  std::vector<double> rhs;                     // per equation: the solve's right side and answer
  std::vector<std::uint8_t> held_nodes;        // per node: prescribed or in a closed contact
  std::vector<double> trial_element_force;     // per element (6 each): its force at u_trial
  std::vector<double> damage_before;           // per element: w before the last damage pass
  std::vector<std::int32_t> changed_elements;  // scratch: elements a damage pass changed
  std::vector<std::uint8_t> moved_nodes;       // scratch: per node, moved since a known pass
  std::vector<std::int32_t> moved_elements;    // scratch: elements with such a node
  std::vector<double> u_solution;              // u + du where the last solve's strains were taken
  std::vector<double> solution_element_force;  // per element (6 each): its force there

  double time = 0.0;                        // at the end of the step attempted
  double load_factor = 0.0;                 // of the step attempted
  StepEnergy energy;                        // released by the attempt's damage passes and re-solves
  std::optional<FirstDamage> first_damage;  // the attempt's, when the run had none yet
  std::vector<EventState> events;           // run events of its damage passes
  int damage_passes = 0;                    // damage passes of the attempt so far
  int solution_passes = -1;  // damage_passes when u_solution's forces were taken; -1: none yet
  bool restraint_grown = false;     // its cascade cut parts loose and the restraint held them
  bool end_out_of_balance = false;  // its last pass dropped moduli and was not re-solved
  bool calls_for_inertia = false;   // its cascade is to go on with inertia (snap_back)
  bool damage_changed = false;      // a damage pass raised some element's damage
  bool contact_changed = false;     // an open-close iteration switched a contact's state
  bool onset_located = false;       // it ends at an undamaged element's onset, whose damage
                                    // runs in the next step, of no length
  double onset_fraction = 1.0;      // when cut: the fraction of it where the first onset lies
  double onset_largest = 0.0;       // when cut: the largest onset ratio at its end

  /// Zeroed arrays for `num_dofs` dofs and `num_equations` equations.
  void resize(std::size_t num_dofs, std::int32_t num_equations);
  /// A new attempt at `time` with `load_factor`: the attempt's findings forgotten.
  void begin_attempt(double at_time, double at_load_factor);
  /// After nodes split (detach_damaged_elements): each new node takes its origin's values.
  void follow_split_nodes(std::span<const std::int32_t> node_origin);
};

}  // namespace rockdd

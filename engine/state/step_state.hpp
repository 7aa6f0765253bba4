#pragma once
// The arrays a time step works on, apart from the model's own fields: what Simulation's step
// loop reads and writes between the stages, kept in one place so the loop is only the loop.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// Per-dof arrays (2 per node) of the step being attempted and of the last committed one.
struct StepState {
  std::vector<double> acceleration;            // committed (Newmark); 0 without inertia
  std::vector<double> f_int, f_ext;            // internal force at the trial or committed u; loads
  std::vector<double> f_ext_old;               // loads of the last committed step
  std::vector<double> reaction, reaction_old;  // constraint forces: this step, last committed
  std::vector<double> reaction_first;          // constraint forces after the step's first
                                               // solve, before its damage cascade
  std::vector<double> u_trial;                 // committed u plus the prescribed increment
  std::vector<double> du;                      // the step's displacement increment
  std::vector<double> f_contact;               // contact spring forces at the trial state
  std::vector<double> positions;               // scratch: X + u for geometry queries
  std::vector<double> damage_force;            // f_int at the step's result, for damage checks
  std::vector<double> restraint_force;         // fragment restraint's force on the increment
  std::vector<double> positions_settled;       // X + u + du where the last damage pass dropped
                                               // the moduli (the snap-back's start)
  std::vector<double> rhs;                     // per equation: the solve's right side and answer
  std::vector<std::uint8_t> held_nodes;        // per node: prescribed or in a closed contact
  double load_factor = 0.0;                    // of the step attempted (committed, after it)
  double committed_stored_energy = 0.0;        // elements and contact springs at the commit
  bool end_out_of_balance = false;    // the attempt's last pass dropped moduli, not re-solved
  bool start_out_of_balance = false;  // the committed state is no equilibrium: as above, or
                                      // nodes split after it
  std::vector<double> committed_strain, committed_stress;  // per element (3 each), at the
                                                           // committed u: dynamic damage energy
  std::vector<double> trial_element_force;     // per element (6 each): its nodal force at u_trial
  std::vector<std::int32_t> changed_elements;  // scratch: elements a damage pass changed

  /// Zeroed arrays for `num_dofs` dofs and `num_equations` equations.
  void resize(std::size_t num_dofs, std::int32_t num_equations);
  /// After nodes split (detach_damaged_elements): each new node takes its origin's values.
  void follow_split_nodes(std::span<const std::int32_t> node_origin);
};

}  // namespace rockdd

#include "engine/state/step_state.hpp"

#include "engine/damage/detachment.hpp"

namespace rockdd {

void StepState::resize(std::size_t num_dofs, std::int32_t num_equations) {
  for (auto* field : {&f_int, &f_ext, &reaction, &reaction_first, &u_trial, &du, &f_contact,
                      &contact_force_solved, &contact_force_sum, &positions, &damage_force,
                      &restraint_force, &positions_settled, &u_solution})
    field->assign(num_dofs, 0.0);
  rhs.assign(static_cast<std::size_t>(num_equations), 0.0);
}

void StepState::begin_attempt(double at_time, double at_load_factor) {
  time = at_time;
  load_factor = at_load_factor;
  energy = {};
  first_damage.reset();
  events.clear();
  damage_passes = 0;
  solution_passes = -1;
  restraint_grown = end_out_of_balance = calls_for_inertia = damage_changed = onset_located =
      contact_changed = false;
  onset_fraction = 1.0;
}

void StepState::follow_split_nodes(std::span<const std::int32_t> node_origin) {
  for (auto* field : {&f_int, &f_ext, &reaction, &reaction_first, &u_trial, &du, &f_contact,
                      &contact_force_solved, &contact_force_sum, &positions, &damage_force,
                      &restraint_force, &positions_settled, &u_solution})
    rockdd::follow_split_nodes(node_origin, *field);
}

}  // namespace rockdd

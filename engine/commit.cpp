// The commit of an accepted step and what follows it: velocities, displacements, stresses,
// contacts and the energy balance; the fracture that detaches broken elements; the committed
// state every later attempt starts from; and the switch to inertia after a snap-back.
#include <algorithm>
#include <cstdio>

#include "engine/assembly/internal_force.hpp"
#include "engine/assembly/modulus_change.hpp"
#include "engine/common/errors.hpp"
#include "engine/common/timers.hpp"
#include "engine/contact/contact_stage.hpp"
#include "engine/damage/damage_stage.hpp"
#include "engine/damage/detachment.hpp"
#include "engine/loading/external_loads.hpp"
#include "engine/output/probes.hpp"
#include "engine/output/run_outputs.hpp"
#include "engine/simulation.hpp"
#include "engine/solver/linear_system.hpp"
#include "engine/time/integrator.hpp"
#include "engine/time/rotation_correction.hpp"
#include "engine/time/snap_back.hpp"
#include "engine/time/step_control.hpp"

namespace rockdd {

void Simulation::commit_step(double dt, const StepControl& control) {
  const std::size_t num_dofs = model_.X.size();
  EnergyAccount& energy = committed_.energy;
  // A quasi-static step's velocity is the one its inertia term implies (inertia_step): a step
  // cut short at an onset, or one of no length, moves no faster for it.
  energy.integrator +=
      update_velocity(analysis_, integrator_, inertia_step(dt, control), trial_.du, bc_.prescribed,
                      bc_.velocity, model_.node_mass, model_.v, committed_.acceleration);
  if (corotational_) {
    // Only blocks that nothing holds turn exactly; the others stay where the solve balanced
    // them against their constraints and contacts.
    trial_.held_nodes.assign(static_cast<std::size_t>(model_.num_nodes()), 0);
    for (std::size_t d = 0; d < num_dofs; ++d)
      if (bc_.prescribed[d]) trial_.held_nodes[d / 2] = 1;
    if (contact_) contact_->mark_touching_nodes(trial_.held_nodes);
    correct_block_rotations(model_, model_.u, trial_.held_nodes, trial_.du, model_.v,
                            committed_.acceleration);
  }
  for (std::size_t d = 0; d < num_dofs; ++d) model_.u[d] += trial_.du[d];
  internal_force_at_commit();
  if (contact_) {
    ScopedTimer timer(report_.timers.contact);
    for (std::size_t d = 0; d < num_dofs; ++d) trial_.positions[d] = model_.X[d] + model_.u[d];
    // The step's contact forces before the commit folds the step's slip into the shear
    // springs' anchors: after it they would count that slip twice.
    std::fill(trial_.f_contact.begin(), trial_.f_contact.end(), 0.0);
    contact_->add_spring_forces(trial_.positions, trial_.f_contact);
    if (contact_->energy_consistent()) balance_acceleration_at_end_contact_forces();
    const double spring_energy_before = committed_.contact_spring_energy;
    const double friction_before = energy.friction;
    committed_.contact_spring_energy = contact_->commit(trial_.positions, energy.friction);
    committed_.contacts = contact_->contacts();
    if (analysis_ == Analysis::dynamic && integrator_ == Integrator::dda) {
      energy.integrator += contact_end_point_loss(
          trial_.contact_force_solved, committed_.contact_force, trial_.du, bc_.prescribed,
          committed_.contact_spring_energy - spring_energy_before,
          energy.friction - friction_before);
      committed_.contact_force = trial_.contact_force_solved;
    }
  }
  fragments_.forces(trial_.du, trial_.restraint_force);
  // The restraint's springs restart from zero force next step: the energy they hold now
  // leaves the balance, a loss of the method (not of the rock) that summary.json reports.
  energy.anchor += fragments_.energy(trial_.du);
  // The constraints' force on the body, and the work of all external forces (trapezoidal).
  // Without inertia a damage cascade runs at fixed boundaries: the step's boundary work is
  // done at the first solve's reactions (record_first_reaction), not at the fallen ones.
  const bool first_reaction = damage_ && analysis_ != Analysis::dynamic;
  double work = 0.0;
  for (std::size_t d = 0; d < num_dofs; ++d) {
    trial_.reaction[d] = constraint_force(bc_.prescribed[d], trial_.f_int[d], trial_.f_contact[d],
                                          trial_.restraint_force[d], trial_.f_ext[d]);
    committed_.residual[d] =
        bc_.prescribed[d]
            ? 0.0
            : trial_.f_ext[d] - trial_.f_int[d] - trial_.f_contact[d] - trial_.restraint_force[d];
    const double reaction = first_reaction ? trial_.reaction_first[d] : trial_.reaction[d];
    work += 0.5 * (committed_.f_ext[d] + committed_.reaction[d] + trial_.f_ext[d] + reaction) *
            trial_.du[d];
  }
  energy.external_work += work;
  energy.add(trial_.energy);
  if (damage_) {
    if (!committed_.first_damage) committed_.first_damage = trial_.first_damage;
    // Where the next step's snap-back starts from, when it starts out of balance.
    committed_.stored_energy = strain_energy(model_, model_.strain, model_.stress) +
                               (contact_ ? committed_.contact_spring_energy : 0.0);
  }
  committed_.out_of_balance = trial_.end_out_of_balance;
  committed_.load_factor = trial_.load_factor;
  std::swap(committed_.f_ext, trial_.f_ext);
  std::swap(committed_.reaction, trial_.reaction);
}

void Simulation::internal_force_at_commit() {
  ScopedTimer timer(report_.timers.assembly);
  const std::size_t element_values = 6 * static_cast<std::size_t>(model_.num_elements());
  // The last solve's strains were taken at this displacement, before the damage pass after it
  // (at most one) dropped some moduli: only the elements that pass changed, and those a
  // block's rotation moved since, are computed again, by the same kernel, and the sum runs in
  // the same order, so f_int is bitwise what a whole pass gives.
  const int passes_since = trial_.damage_passes - trial_.solution_passes;
  if (trial_.solution_passes < 0 || passes_since > 1 ||
      trial_.solution_element_force.size() != element_values) {
    committed_.element_force.resize(element_values);
    compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, trial_.f_int,
                           corotational_, committed_.element_force);
    return;
  }
  elements_moved_between(model_, trial_.u_solution, model_.u, trial_.moved_nodes,
                         trial_.moved_elements);
  if (passes_since == 1) {
    std::vector<std::int32_t>& stale = trial_.moved_elements;
    changed_elements(model_, trial_.damage_before, trial_.changed_elements);
    const auto moved = static_cast<std::ptrdiff_t>(stale.size());
    stale.insert(stale.end(), trial_.changed_elements.begin(), trial_.changed_elements.end());
    std::inplace_merge(stale.begin(), stale.begin() + moved, stale.end());
    stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
  }
  refresh_element_forces(model_, model_.u, trial_.moved_elements, trial_.solution_element_force,
                         corotational_, model_.strain, model_.stress);
  sum_element_forces(model_, coloring_, trial_.solution_element_force, trial_.f_int);
  std::swap(committed_.element_force, trial_.solution_element_force);
  trial_.solution_passes = -1;  // its forces now belong to the committed state
}

void Simulation::record_committed_state(bool detached) {
  committed_.damage = model_.damage;
  committed_.strain = model_.strain;
  committed_.stress = model_.stress;
  if (trial_.restraint_grown && !detached) {
    // Supports of parts that the step's cascade cut loose end with it (a detachment would have
    // rebuilt the restraint already): the restraint of the committed parts holds again.
    fragments_ = FragmentRestraint(model_, current_edges(), bc_, scene_.fracture.fragment_stiffness,
                                   scene_.fracture.loose_part_support);
    system_->invalidate();
  }
  trial_.restraint_grown = false;
  fragments_.restart();  // the next step's springs hold from where it starts
  committed_.restraint = fragments_;
}

const EdgeAdjacency& Simulation::current_edges() {
  if (edges_.neighbor.size() != model_.conn.size())
    edges_ = build_edge_adjacency(model_.conn, "fracture");
  return edges_;
}

bool Simulation::detach_fractured_elements() {
  ScopedTimer timer(report_.timers.detachment);
  std::vector<double> threshold(static_cast<std::size_t>(model_.num_elements()));
  for (std::int32_t e = 0; e < model_.num_elements(); ++e)
    threshold[e] = damage_->detach_threshold(model_, e);
  current_edges();
  const Detachment detachment = detach_damaged_elements(model_, threshold, detached_, edges_);
  if (detachment.detached == 0) return false;
  report_.counters.detached_elements += detachment.detached;
  committed_.out_of_balance = true;
  // Everything built on the nodes follows the split: the step state, the constraints and
  // loads (named curves carried their element sides over), probes, colouring and contacts.
  trial_.follow_split_nodes(detachment.node_origin);
  committed_.follow_split_nodes(detachment.node_origin);
  bc_ = build_boundary_conditions(scene_, model_);
  // Without inertia a piece that fracture cut loose is held by nothing but the weak fragment
  // restraint (built below; enough for lone elements): the specimen has failed, and a static
  // analysis cannot follow it.
  if (analysis_ == Analysis::static_)
    if (const std::optional<FreeBlock> free = find_free_block(model_, bc_, 2)) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "step %ld: fracture cut loose block %d (%d elements of body '%s'), which "
                    "nothing holds in %s in a static analysis: the specimen has failed; use "
                    "analysis = \"quasi-static\" or \"dynamic\" to follow it further",
                    report_.counters.steps + 1, free->block, free->elements, free->body.c_str(),
                    free->motion.c_str());
      throw RunFailure(buf);
    }
  reference_loads_ = build_reference_loads(scene_, model_);
  trial_.rhs.assign(static_cast<std::size_t>(bc_.num_equations), 0.0);
  auto probes = std::make_unique<Probes>(scene_, model_);
  probes->carry_state_from(*probes_);
  probes_ = std::move(probes);
  coloring_ = color_elements(model_.conn, model_.num_nodes());
  if (analysis_ != Analysis::dynamic)
    fragments_ = FragmentRestraint(model_, edges_, bc_, scene_.fracture.fragment_stiffness,
                                   scene_.fracture.loose_part_support);
  if (analysis_ != Analysis::dynamic && corotational_) turn_loose_block_frames();
  // edges_ followed this detachment's node splits: the new blocks' boundary without a sort.
  auto contact = std::make_unique<ContactStage>(scene_, model_, edges_, analysis_, integrator_);
  if (contact_) contact->carry_contacts_from(*contact_, committed_.contacts);
  contact_ = std::move(contact);
  rebuild_layout();
  recompute_committed_forces();
  return true;
}

void Simulation::turn_loose_block_frames() {
  const std::vector<std::uint8_t> free = unrestrained_blocks(model_, bc_);
  std::vector<std::int32_t> loose;
  for (std::int32_t e = 0; e < model_.num_elements(); ++e)
    if (free[model_.element_block[e]]) loose.push_back(e);
  update_element_rotations(model_, model_.u, loose);
}

void Simulation::recompute_committed_forces() {
  // A split node's copies took their origin's loads and constraint force: a copy that left
  // the constraint would do work with a reaction it no longer has, and two copies would
  // count one node's weight twice. Both are taken anew at the committed state.
  const std::size_t num_dofs = model_.X.size();
  committed_.element_force.resize(6 * static_cast<std::size_t>(model_.num_elements()));
  compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, trial_.f_int,
                         corotational_, committed_.element_force);
  std::fill(trial_.f_contact.begin(), trial_.f_contact.end(), 0.0);
  for (std::size_t d = 0; d < num_dofs; ++d) trial_.positions[d] = model_.X[d] + model_.u[d];
  contact_->add_committed_forces(trial_.positions, trial_.f_contact);
  fragments_.forces(trial_.du, trial_.restraint_force);
  for (std::size_t d = 0; d < num_dofs; ++d) {
    committed_.f_ext[d] = committed_.load_factor * reference_loads_[d];
    committed_.reaction[d] =
        constraint_force(bc_.prescribed[d], trial_.f_int[d], trial_.f_contact[d],
                         trial_.restraint_force[d], committed_.f_ext[d]);
    committed_.residual[d] = bc_.prescribed[d]
                                 ? 0.0
                                 : committed_.f_ext[d] - trial_.f_int[d] - trial_.f_contact[d] -
                                       trial_.restraint_force[d];
  }
}

void Simulation::balance_acceleration_at_end_contact_forces() {
  // Newmark's update left an acceleration that balances the contact forces the solve took,
  // which stand for the sum of the step's start and end forces (mean normal forces, friction
  // at its end); the next step must start from one that balances the springs' end forces as
  // they are. The difference is that sum less the two end forces.
  const std::size_t num_dofs = model_.X.size();
  std::vector<double>& sum = trial_.contact_force_sum;
  std::fill(sum.begin(), sum.end(), 0.0);
  contact_->add_solve_forces(trial_.positions, sum);
  for (std::size_t d = 0; d < num_dofs; ++d)
    if (!bc_.prescribed[d])
      committed_.acceleration[d] +=
          (sum[d] - committed_.contact_force[d] - trial_.f_contact[d]) / model_.node_mass[d / 2];
  committed_.contact_force = trial_.f_contact;
}

void Simulation::balance_acceleration() {
  // Starting from a = 0 instead would misplace every later velocity by the unbalanced force
  // (g dt / 2 for a body under gravity at rest).
  // With Newmark's energy-consistent contacts the next step's solve takes the place of the
  // contact forces the acceleration holds: it must know them.
  if (contact_ && contact_->energy_consistent()) committed_.contact_force = trial_.f_contact;
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    committed_.acceleration[d] =
        bc_.prescribed[d] || analysis_ != Analysis::dynamic
            ? 0.0
            : (committed_.f_ext[d] - trial_.f_int[d] - trial_.f_contact[d]) /
                  model_.node_mass[d / 2];
}

void Simulation::follow_cascade_with_inertia(long step, double time, double end_time,
                                             StepControl& control) {
  const double dt = snap_back_time_step(scene_, model_);
  // Every later step is dynamic: a run that only time.end ends would need that many steps of
  // dt. Said now rather than left to run for days.
  constexpr double kMostDynamicSteps = 1e6;
  if (!scene_.time.stop_at_softening && (end_time - time) / dt > kMostDynamicSteps) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "step %ld: a damage cascade is followed with inertia from here "
                  "(fracture.snap_back = \"dynamic\") at dt %.3g s, and time.end leaves %.3g s: "
                  "%.3g steps; end the run sooner (time.end, or time.stop_at_softening)",
                  step, dt, end_time - time, (end_time - time) / dt);
    throw RunFailure(buf);
  }
  analysis_ = Analysis::dynamic;
  integrator_ = Integrator::newmark;  // neither damps nor adds: the release becomes motion
  control.restart_at(dt);
  report_.inertia_switch = InertiaSwitch{step, time, dt};
  // Inertia holds loose blocks now; contacts lose the sliding springs of steps without it.
  fragments_ = committed_.restraint = FragmentRestraint();
  std::fill(trial_.restraint_force.begin(), trial_.restraint_force.end(), 0.0);
  if (contact_) contact_->set_analysis(analysis_, integrator_);  // same contacts, same pattern
  system_->invalidate();
  // The last pass's modulus drop left the committed state out of balance.
  balance_acceleration();
}

EnergyBalance Simulation::energy() const {
  EnergyBalance e;
  // Without inertia every step starts at rest: the velocity written out is the last step's
  // mean, and the energy of that motion is the scheme's loss (quasi_static), not held.
  // A prescribed dof moves as its device says: the device's energy, not the body's (no work of
  // the impulse that set it going is booked either).
  if (analysis_ == Analysis::dynamic)
    for (std::size_t d = 0; d < model_.v.size(); ++d)
      if (!bc_.prescribed[d])
        e.kinetic += 0.5 * model_.node_mass[d / 2] * model_.v[d] * model_.v[d];
  e.strain = strain_energy(model_, model_.strain, model_.stress) +
             (contact_ ? committed_.contact_spring_energy : 0.0);
  const EnergyAccount& account = committed_.energy;
  e.external_work = account.external_work;
  e.dissipated = account.damage + (contact_ ? account.friction : 0.0);
  e.snap_back = account.snap_back;
  e.integrator = account.integrator;
  e.anchor = account.anchor;
  e.initial = account.initial;
  e.quasi_static = account.quasi_static;
  return e;
}

}  // namespace rockdd

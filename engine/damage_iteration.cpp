// The damage iteration of a step attempt (METHOD.md "Elastic damage"): the laws evaluated at
// each solve, the re-solve's preparation when elements newly damage, and the energy the passes
// release (damage and snap-back).
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/assembly/internal_force.hpp"
#include "engine/assembly/modulus_change.hpp"
#include "engine/common/timers.hpp"
#include "engine/contact/contact_stage.hpp"
#include "engine/damage/damage_energy.hpp"
#include "engine/damage/damage_stage.hpp"
#include "engine/simulation.hpp"
#include "engine/solver/linear_system.hpp"
#include "engine/time/step_control.hpp"

namespace rockdd {

namespace {
// The restraint relaxes when its springs hold more than fracture.restraint_relaxation of the
// stored energy (by default a tenth of what the energy balance may leave open), down to
// kRestraintRelaxed of that share.
constexpr double kRestraintRelaxed = 1e-3;
// Relaxations go on while each leaves the springs less than this share of what they held.
constexpr double kRelaxationFall = 0.5;
constexpr int kMaxRestraintRelaxations = 30;
}  // namespace

void Simulation::strain_at_result() {
  // The internal-force pass, as at a step's start: assembly's work, not the damage laws'.
  ScopedTimer timer(report_.timers.assembly);
  const std::size_t num_dofs = model_.X.size();
  for (std::size_t d = 0; d < num_dofs; ++d) trial_.u_solution[d] = model_.u[d] + trial_.du[d];
  // Each element's force is kept: the commit, at the same displacement, recomputes only the
  // elements whose modulus the last pass dropped (and any a block's rotation moved).
  trial_.solution_element_force.resize(6 * static_cast<std::size_t>(model_.num_elements()));
  compute_internal_force(model_, coloring_, trial_.u_solution, model_.strain, model_.stress,
                         trial_.damage_force, corotational_, trial_.solution_element_force);
  trial_.solution_passes = trial_.damage_passes;
}

DamageChange Simulation::evaluate_damage(bool start_onsets) {
  ScopedTimer timer(report_.timers.damage);
  trial_.damage_before = model_.damage;
  const DamageChange change = damage_->evaluate(model_, scene_.fracture.damage_band, start_onsets);
  ++report_.counters.damage_stage_passes;
  if (change.grown > 0) {
    trial_.damage_changed = true;
    // Without carried velocity the pass drops the moduli at its own strain and re-solves from
    // there. A dynamic step instead integrates the whole step with the new moduli, from the
    // committed state: that is where its modulus drop takes the energy.
    trial_.energy.damage +=
        released_by_damage(model_, trial_.damage_before,
                           analysis_ == Analysis::dynamic ? committed_.strain : model_.strain);
  }
  ++trial_.damage_passes;
  if (change.newly_damaged > 0) {
    if (!committed_.first_damage && !trial_.first_damage)
      trial_.first_damage = locate_first_damage(model_, report_.counters.steps + 1, trial_.time);
    note_damage_events();
  }
  return change;
}

OnsetSearch Simulation::locate_onset(double target) {
  ScopedTimer timer(report_.timers.damage);
  ++report_.counters.damage_stage_passes;
  return damage_->locate_onset(model_, committed_.strain, committed_.stress, target);
}

void Simulation::note_damage_events() {
  auto pending = [&](const char* name) {
    return !committed_.has_event(name) &&
           std::none_of(trial_.events.begin(), trial_.events.end(),
                        [&](const EventState& state) { return state.event.name == name; });
  };
  std::vector<std::pair<const char*, std::vector<double>>> found;
  if (pending("first_damage")) found.emplace_back("first_damage", std::vector<double>{});
  if (pending("first_separation"))
    if (std::vector<double> parts = damage_->separation().separated_parts(model_); !parts.empty())
      found.emplace_back("first_separation", std::move(parts));
  for (auto& [name, parts] : found) {
    EventState state{{name,
                      report_.counters.steps + 1,
                      trial_.damage_passes,
                      trial_.time,
                      0,
                      std::move(parts),
                      {}},
                     model_};
    state.event.damaged_elements = static_cast<std::int32_t>(
        std::count_if(model_.damage.begin(), model_.damage.end(), [](double w) { return w > 0; }));
    // The frame shows the pass's solution, where its strains and damage stand.
    for (std::size_t d = 0; d < model_.u.size(); ++d) state.model.u[d] += trial_.du[d];
    trial_.events.push_back(std::move(state));
  }
}

void Simulation::record_first_reaction() {
  // f_int at the solution is the damage check's (before this pass drops any modulus).
  const std::size_t num_dofs = model_.X.size();
  std::fill(trial_.reaction_first.begin(), trial_.reaction_first.end(), 0.0);
  if (contact_) {
    for (std::size_t d = 0; d < num_dofs; ++d)
      trial_.positions[d] = model_.X[d] + model_.u[d] + trial_.du[d];
    contact_->add_spring_forces(trial_.positions, trial_.reaction_first);
  }
  for (std::size_t d = 0; d < num_dofs; ++d)
    trial_.reaction_first[d] =
        constraint_force(bc_.prescribed[d], trial_.damage_force[d], trial_.reaction_first[d],
                         trial_.restraint_force[d], trial_.f_ext[d]);
}

double Simulation::measure_snap_back(int pass, bool settle_start, const DamageChange& change,
                                     double released_before, double settled_energy) {
  if (!(pass > 1 || change.grown > 0 || settle_start)) return settled_energy;
  const std::size_t num_dofs = model_.X.size();
  const double stored = stored_energy();  // at this solve, before its modulus drop
  if (pass > 1 || settle_start) {
    // The work done between the two states: in the first solve, the boundaries' and the
    // loads' over the step's increment; later, the loads' alone (the boundaries hold).
    double work = 0.0;
    for (std::size_t d = 0; d < num_dofs; ++d)
      work += pass == 1 ? 0.5 *
                              (committed_.f_ext[d] + committed_.reaction[d] + trial_.f_ext[d] +
                               trial_.reaction_first[d]) *
                              trial_.du[d]
                        : trial_.f_ext[d] * (trial_.positions[d] - trial_.positions_settled[d]);
    const double friction =
        contact_ ? contact_->friction_work_between(trial_.positions_settled, trial_.positions)
                 : 0.0;
    trial_.energy.add_snap_back(settled_energy - stored + work - friction);
  }
  std::swap(trial_.positions, trial_.positions_settled);
  return stored - (trial_.energy.damage - released_before);
}

double Simulation::stored_energy() {
  // The mass term c M of a quasi-static step is not stored: it holds the step's motion, which
  // the next step starts without (the velocity reset), so what goes into it is released.
  const std::size_t num_dofs = model_.X.size();
  for (std::size_t d = 0; d < num_dofs; ++d)
    trial_.positions[d] = model_.X[d] + model_.u[d] + trial_.du[d];
  double energy =
      strain_energy(model_, model_.strain, model_.stress) + fragments_.energy(trial_.du);
  if (contact_) energy += contact_->spring_energy_at(trial_.positions);
  return energy;
}

void Simulation::prepare_next_pass(double mass_coefficient) {
  changed_elements(model_, trial_.damage_before, trial_.changed_elements);
  hold_parts_cut_loose();
  prepare_system(mass_coefficient);  // the moduli's change folded into the factor, or assembled
  // The next solve's internal force at u_trial under the new moduli: bitwise what a full
  // recomputation gives (the same kernel per element, summed in the same order).
  ScopedTimer timer(report_.timers.assembly);
  refresh_element_forces(model_, trial_.u_trial, trial_.changed_elements,
                         trial_.trial_element_force, corotational_);
  sum_element_forces(model_, coloring_, trial_.trial_element_force, trial_.f_int);
}

void Simulation::hold_parts_cut_loose() {
  if (analysis_ == Analysis::dynamic) return;  // inertia holds them
  const bool broke = std::any_of(
      trial_.changed_elements.begin(), trial_.changed_elements.end(),
      [&](std::int32_t e) { return trial_.damage_before[e] < 1.0 && model_.damage[e] >= 1.0; });
  if (!broke) return;
  FragmentRestraint held(model_, current_edges(), bc_, scene_.fracture.fragment_stiffness,
                         scene_.fracture.loose_part_support);
  if (held.same_springs(fragments_)) return;
  held.anchor_new_springs(fragments_, trial_.du);
  fragments_ = std::move(held);
  ++report_.counters.parts_cut_loose;
  trial_.restraint_grown = true;
  // The springs act on the step's increment; the next solve starts again from u_trial.
  std::vector<double> trial_increment(model_.X.size());
  for (std::size_t d = 0; d < trial_increment.size(); ++d)
    trial_increment[d] = trial_.u_trial[d] - model_.u[d];
  fragments_.forces(trial_increment, trial_.restraint_force);
  system_->invalidate();  // K takes the new springs
}

void Simulation::relax_restraint(long step, int retries, const InertiaTerms& inertia,
                                 const StepControl& control) {
  if (fragments_.num_dofs() == 0) return;
  const std::size_t num_dofs = model_.X.size();
  double held = fragments_.energy(trial_.du);
  if (held <= 0.0) return;
  const double stored = stored_energy();
  const double trigger = scene_.fracture.restraint_relaxation;
  if (trigger == 0.0 || held <= trigger * stored) return;
  const double floor = kRestraintRelaxed * trigger * stored;
  const double reach = contact_ && !scene_.time.max_step_displacement
                           ? contact_->parameters().reach
                           : std::numeric_limits<double>::infinity();
  const auto set_restraint_force = [&] {
    for (std::size_t d = 0; d < num_dofs; ++d)
      trial_.positions[d] = trial_.u_trial[d] - model_.u[d];  // the trial increment
    fragments_.forces(trial_.positions, trial_.restraint_force);
  };
  for (int i = 0; i < kMaxRestraintRelaxations && held > floor; ++i) {
    const FragmentRestraint before = fragments_;
    const std::vector<double> du_before = trial_.du;
    std::vector<Contact> contacts_before;
    std::vector<ContactSprings> springs_before;
    if (contact_) {
      contacts_before = contact_->contacts();
      springs_before = contact_->springs();
    }
    fragments_.follow(trial_.du);
    set_restraint_force();
    const bool settled = open_close_iteration(step, retries, inertia, nullptr);
    ++report_.counters.restraint_relaxations;
    double largest = 0.0;
    for (const double du : trial_.du) largest = std::max(largest, std::abs(du));
    const double now = fragments_.energy(trial_.du);
    // What the springs hold that does not fall when they let go is a part that only they
    // hold (a mechanism a force drives), and a part that would leave the step's reach must
    // not: both stay where the springs held them.
    if (!settled || now >= kRelaxationFall * held || !control.displacement_ok(largest) ||
        largest > reach) {
      // Taken back exactly: a re-solve could settle the contacts elsewhere.
      fragments_ = before;
      set_restraint_force();
      trial_.du = du_before;
      if (contact_) {
        const bool switched = contact_->springs() != springs_before;
        contact_->restore_contacts(std::move(contacts_before));
        // The factor holds the springs the relaxation switched: back to the earlier ones.
        if (switched)
          system_->add_contact_springs(contact_->spring_matrices(model_.num_elements()), false);
      }
      break;
    }
    held = now;
  }
}

}  // namespace rockdd

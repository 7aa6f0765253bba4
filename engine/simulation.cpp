#include "engine/simulation.hpp"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_state.hpp"
#include "engine/assembly/internal_force.hpp"
#include "engine/assembly/modulus_change.hpp"
#include "engine/contact/contact_stage.hpp"
#include "engine/damage/damage_stage.hpp"
#include "engine/damage/detachment.hpp"
#include "engine/damage/fragment_restraint.hpp"
#include "engine/errors.hpp"
#include "engine/loading/external_loads.hpp"
#include "engine/mesh/mesh_cache.hpp"
#include "engine/output/probes.hpp"
#include "engine/process_clock.hpp"
#include "engine/time/rotation_correction.hpp"
#include "engine/time/snap_back.hpp"
#include "kernels/damage_law.hpp"

namespace rockdd {
namespace {

/// Open-close iterations allowed in one step before it is redone with dt / 2. Without inertia
/// a sliding contact approaches its friction limit geometrically (sliding_stiffness), and
/// those iterations mostly reuse the factor: they get more.
constexpr int kMaxOpenCloseIterations = 12;
constexpr int kMaxOpenCloseIterationsWithoutInertia = 30;
/// Contacts that swing between answers may settle on their last one only in a step already
/// redone this many times (a smaller dt did not help), and only in its closing iterations.
constexpr int kRetriesBeforeSettling = 2;
constexpr int kSettlingIterations = 2;

/// Doublings of the open-close force tolerance allowed to a chattering step (at most 4x).
constexpr int kMaxRelaxationDoublings = 2;

/// Rotation (rad) an element may turn before the stiffness is reassembled in its new frame.
constexpr double kFrameTolerance = 1e-3;

/// The constraints' force on the body at a dof: at a prescribed one, what the body's own
/// forces leave unbalanced there (f_int + f_contact + restraint - f_ext); elsewhere 0.
double constraint_force(bool prescribed, double f_int, double f_contact, double restraint,
                        double f_ext) {
  return prescribed ? f_int + f_contact + restraint - f_ext : 0.0;
}

/// Run length: `end`, or `steps` x dt, or one step of 1 s in a static scene without [time].
double end_time_of(const Scene& scene) {
  if (scene.time.end) return *scene.time.end;
  return static_cast<double>(scene.time.steps.value_or(1)) * scene.time.dt;
}

const char* analysis_name(Analysis a) {
  switch (a) {
    case Analysis::static_:
      return "static";
    case Analysis::quasi_static:
      return "quasi-static";
    case Analysis::dynamic:
      return "dynamic";
  }
  return "";
}

}  // namespace

std::filesystem::path run_folder(const Scene& scene, const RunOptions& options) {
  if (!options.out_dir.empty()) return options.out_dir;
  return (options.out_root.empty() ? scene.output.dir : options.out_root) / scene.name;
}

Simulation::Simulation(Scene scene, Model model, std::optional<MeshCacheSlot> mesh_slot)
    : scene_(std::move(scene)),
      analysis_(scene_.analysis),
      integrator_(scene_.time.integrator),
      model_(std::move(model)),
      mesh_slot_(std::move(mesh_slot)) {
  ScopedTimer timer(setup_timers_.other);
  // Blocks that move turn: their strain is measured in co-rotated frames. A static analysis
  // restrains every block and solves once, small strain (f_int = K u exactly).
  corotational_ = analysis_ != Analysis::static_;
  bc_ = build_boundary_conditions(scene_, model_);
  if (analysis_ == Analysis::static_) check_static_restraint(scene_, model_, bc_);
  reference_loads_ = build_reference_loads(scene_, model_);
  probes_ = std::make_unique<Probes>(scene_, model_);

  {
    ScopedTimer layout_timer(timers_.layout);
    coloring_ = color_elements(model_.conn, model_.num_nodes());
  }
  if (!scene_.joints.empty()) contact_ = std::make_unique<ContactStage>(scene_, model_, analysis_);
  if (!model_.tensile_strength.empty()) {
    damage_ = std::make_unique<DamageStage>(scene_, model_);
    committed_damage_ = model_.damage;
  }
  rebuild_layout();
  // The step loop's timers start at zero: what the first layout took is set-up.
  std::swap(setup_timers_.layout, timers_.layout);
  std::swap(setup_timers_.analysis, timers_.analysis);

  state_.resize(model_.X.size(), bc_.num_equations);
  for (const InitialSpec& init : scene_.initial) {
    // Rigid motion of the body: v = v0 + omega x (x - centroid).
    const auto& bodies = model_.sets.bodies;
    const auto body = std::find(bodies.begin(), bodies.end(), init.body) - bodies.begin();
    double cx = 0, cy = 0, m = 0;
    std::vector<std::uint8_t> in(static_cast<std::size_t>(model_.num_nodes()), 0);
    for (std::int32_t e = 0; e < model_.num_elements(); ++e)
      if (model_.element_body[e] == body)
        for (int k = 0; k < 3; ++k) in[model_.conn[3 * e + k]] = 1;
    for (std::int32_t n = 0; n < model_.num_nodes(); ++n)
      if (in[n]) {
        cx += model_.node_mass[n] * model_.X[2 * n];
        cy += model_.node_mass[n] * model_.X[2 * n + 1];
        m += model_.node_mass[n];
      }
    if (m <= 0)
      throw InputError(scene_.file.string(), "initial.body", "no body named '" + init.body + "'");
    cx /= m;
    cy /= m;
    for (std::int32_t n = 0; n < model_.num_nodes(); ++n)
      if (in[n]) {
        model_.v[2 * n] = init.velocity[0] - init.angular_velocity * (model_.X[2 * n + 1] - cy);
        model_.v[2 * n + 1] = init.velocity[1] + init.angular_velocity * (model_.X[2 * n] - cx);
      }
  }
}

Simulation::~Simulation() {
  try {
    await_analysis();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a failed analysis no one will use
  }
}

void Simulation::rebuild_layout() {
  await_analysis();  // the solver's last analysis is replaced
  ScopedTimer timer(timers_.layout);
  std::vector<std::int32_t> conn = model_.conn;
  if (contact_) {
    const std::vector<std::int32_t> triples = contact_->triples();
    conn.insert(conn.end(), triples.begin(), triples.end());
  }
  layout_ = build_sparsity_pattern(conn, model_.num_nodes(), bc_.equation);
  // CHOLMOD's analysis needs the pattern alone: it runs beside the scatter map and the
  // assembly (the same analysis whatever runs beside it), and the solver waits for it before
  // it factorizes.
  if (bc_.num_equations > 0) {
    analysis_pending_ = true;
    analysis_task_.run([this] {
      analyze_layout();
      mesh_slot_.reset();  // later layouts follow the contacts: computed each time, not stored
    });
  } else {
    mesh_slot_.reset();
  }
  build_scatter_map(conn, bc_.equation, layout_);
  values_.assign(static_cast<std::size_t>(layout_.pattern.nnz()), 0.0);
  if (contact_) base_values_.assign(values_.size(), 0.0);
  factorized_mass_coefficient_ = -1.0;  // the values must be assembled into the new pattern
}

void Simulation::await_analysis() {
  if (!analysis_pending_) return;
  ScopedTimer timer(timers_.analysis);
  analysis_pending_ = false;
  analysis_task_.wait();  // rethrows what the analysis threw
}

void Simulation::analyze_layout() {
  const SparsityPattern& pattern = layout_.pattern;
  if (!mesh_slot_) {
    solver_.analyze(pattern);
    return;
  }
  // The stored entry holds the pattern it was computed for: another restraint, contact or
  // model of the same mesh is a miss, never another pattern's ordering.
  const std::string key = solver_.ordering_key();
  if (std::optional<CachedOrdering> stored =
          read_cached_ordering(*mesh_slot_, key, pattern.col_ptr, pattern.row_idx)) {
    if (const std::optional<FillOrdering> method = fill_ordering_from_name(stored->method)) {
      solver_.analyze_given(pattern, stored->perm, *method);
      ordering_cache_ = MeshCacheOutcome::hit;
      return;
    }
  }
  solver_.analyze(pattern);
  write_cached_ordering(
      *mesh_slot_, key, pattern.col_ptr, pattern.row_idx,
      {solver_.permutation(), std::string(fill_ordering_name(solver_.stats().ordering))});
  ordering_cache_ = MeshCacheOutcome::miss;
}

void Simulation::prepare_system(double mass_coefficient) {
  if (mass_coefficient == factorized_mass_coefficient_ || bc_.num_equations == 0) return;
  {
    ScopedTimer timer(timers_.assembly);
    std::span<double> target =
        contact_ ? std::span<double>(base_values_) : std::span<double>(values_);
    assemble_stiffness(model_, coloring_, layout_, bc_.equation, mass_coefficient, target);
    fragments_.add_stiffness(bc_.equation, layout_.diagonal, target);
    values_incremental_ = false;
  }
  factorized_mass_coefficient_ = mass_coefficient;
  if (contact_) return;  // factorized in every open-close iteration, with the springs
  await_analysis();
  ScopedTimer timer(timers_.factorization);
  solver_.factorize(values_.data());
}

void Simulation::solve_iteration(long step, const InertiaTerms& inertia, bool factor_current) {
  const std::size_t num_dofs = model_.X.size();
  if (contact_) {
    {
      ScopedTimer timer(timers_.contact);
      std::copy(base_values_.begin(), base_values_.end(), values_.begin());
      std::fill(state_.f_contact.begin(), state_.f_contact.end(), 0.0);
      for (std::size_t d = 0; d < num_dofs; ++d)
        state_.positions[d] = model_.X[d] + state_.u_trial[d];
      contact_->add_springs(state_.positions, layout_, model_.num_elements(), values_,
                            state_.f_contact);
    }
    await_analysis();
    ScopedTimer timer(timers_.factorization);
    if (bc_.num_equations > 0 && !factor_current) solver_.factorize(values_.data());
  }
  for (std::size_t d = 0; d < num_dofs; ++d) {
    const std::int32_t eq = bc_.equation[d];
    if (eq < 0) continue;
    const double m = model_.node_mass[d / 2];
    state_.rhs[eq] = state_.f_ext[d] - state_.f_int[d] - state_.f_contact[d] -
                     state_.restraint_force[d] +
                     m * (inertia.velocity_coefficient * model_.v[d] +
                          inertia.acceleration_coefficient * state_.acceleration[d]);
  }
  if (bc_.num_equations > 0) {
    ScopedTimer timer(timers_.solve);
    solve_system();
  }
  for (std::size_t d = 0; d < num_dofs; ++d) {
    if (bc_.equation[d] >= 0)
      state_.du[d] = state_.u_trial[d] - model_.u[d] + state_.rhs[bc_.equation[d]];
    if (!std::isfinite(state_.du[d])) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "step %ld: the displacement increment of node %zu is not finite "
                    "(check stiffness contrasts, restraints and dt)",
                    step, d / 2);
      throw RunFailure(buf);
    }
  }
}

bool Simulation::attempt_step(long step, int retries, double dt, double load_factor,
                              StepControl& control) {
  const InertiaTerms inertia = inertia_terms(analysis_, integrator_, dt);
  state_.load_factor = load_factor;
  const std::size_t num_dofs = model_.X.size();
  inertia_called_for_ = false;
  if (damage_) {
    attempt_first_damage_.reset();
    energy_.begin_attempt();
    if (retries > 0 && model_.damage != committed_damage_) {
      model_.damage = committed_damage_;
      factorized_mass_coefficient_ = -1.0;  // the moduli changed back
    }
    // Supports of parts that the last attempt's cascade cut loose end with it: the restraint
    // of the committed state holds again.
    if (loose_parts_held_) {
      fragments_ = FragmentRestraint(model_, bc_, scene_.fracture.fragment_stiffness,
                                     scene_.fracture.loose_part_support);
      loose_parts_held_ = false;
      factorized_mass_coefficient_ = -1.0;
    }
    // Each step starts from a freshly assembled matrix: folded changes do not accumulate
    // round-off from step to step.
    if (values_incremental_) factorized_mass_coefficient_ = -1.0;
    if (analysis_ == Analysis::dynamic) {
      ScopedTimer timer(timers_.damage);
      state_.committed_strain.resize(model_.strain.size());
      state_.committed_stress.resize(model_.stress.size());
      compute_internal_force(model_, coloring_, model_.u, state_.committed_strain,
                             state_.committed_stress, state_.damage_force, corotational_);
    }
  }
  if (contact_) {
    bool changed = false;
    {
      ScopedTimer timer(timers_.contact);
      for (std::size_t d = 0; d < num_dofs; ++d) state_.positions[d] = model_.X[d] + model_.u[d];
      changed = contact_->detect(state_.positions);
    }
    if (changed) rebuild_layout();
    if (analysis_ != Analysis::dynamic) contact_->set_force_scale(element_force_scale());
  }
  // Co-rotation: the stiffness follows the elements' frames once any has turned by more than
  // kFrameTolerance since K was assembled (the internal force always uses the exact frames).
  if (corotational_ && largest_rotation_change(model_, model_.u) > kFrameTolerance) {
    update_element_rotations(model_, model_.u);
    factorized_mass_coefficient_ = -1.0;
  }
  prepare_system(inertia.mass_coefficient);

  for (std::size_t d = 0; d < num_dofs; ++d) {
    state_.du[d] = bc_.prescribed[d] ? bc_.velocity[d] * dt : 0.0;
    state_.u_trial[d] = model_.u[d] + state_.du[d];
    state_.f_ext[d] = load_factor * reference_loads_[d];
  }
  {
    ScopedTimer timer(timers_.assembly);
    // Each element's force is kept: a damage pass recomputes only the elements it changed.
    state_.trial_element_force.resize(6 * static_cast<std::size_t>(model_.num_elements()));
    compute_internal_force(model_, coloring_, state_.u_trial, model_.strain, model_.stress,
                           state_.f_int, corotational_, state_.trial_element_force);
    for (std::size_t d = 0; d < num_dofs; ++d) state_.du[d] = state_.u_trial[d] - model_.u[d];
    fragments_.forces(state_.du, state_.restraint_force);
  }
  // The damage iteration (METHOD.md): while elements newly damage, re-solve the same step
  // with their reduced moduli. Without carried velocity each re-solve jumps to the next
  // equilibrium: the energy the rock gives up on the way (less the work of the loads and of
  // friction) is what a dynamic run would turn into motion. It is measured, as snap-back.
  // A step may also start out of balance: the last step's final pass dropped moduli without a
  // re-solve (damage that grew without new onsets), or a split node no longer passes the
  // force it carried between the elements around it. The first solve re-settles that along
  // with the step's boundary increment; it is snap-back too, measured from the committed state.
  const bool count_snap_back = analysis_ != Analysis::dynamic;
  const bool settle_start = count_snap_back && damage_ && state_.start_out_of_balance;
  double settled_energy = 0.0;  // stored energy just after the last pass dropped the moduli
  if (settle_start) {
    settled_energy = state_.committed_stored_energy;
    for (std::size_t d = 0; d < num_dofs; ++d)
      state_.positions_settled[d] = model_.X[d] + model_.u[d];
  }
  bool factor_current = false;  // a folded damage pass left the factor holding the next system
  for (int pass = 1;; ++pass) {
    if (!open_close_iteration(step, retries, inertia, control, factor_current)) return false;
    factor_current = false;
    if (!damage_) break;
    const double released_before = energy_.attempt_damage;
    const DamageChange change = evaluate_damage();
    // Without inertia the boundaries move in the first solve only; the cascade after it runs
    // at fixed boundaries, so the step's work is done at the first solve's reactions.
    if (pass == 1 && count_snap_back) record_first_reaction();
    if (count_snap_back)
      settled_energy =
          measure_snap_back(pass, settle_start, change, released_before, settled_energy);
    // The last pass's modulus drop is not re-solved: the next step starts from it.
    state_.end_out_of_balance = change.grown > 0;
    if (change.newly_damaged == 0) break;
    // With snap_back = "dynamic" the cascade goes on with inertia from here, in the steps
    // after this one.
    if (cascade_calls_for_inertia(scene_.fracture, analysis_, pass)) {
      inertia_called_for_ = true;
      break;
    }
    if (pass >= scene_.fracture.max_damage_passes) {
      ++stats_.damage_limit_hits;
      break;
    }
    ++stats_.damage_iterations;
    factor_current = prepare_next_pass(inertia.mass_coefficient, change.grown > 0);
  }
  return increment_acceptable(step, control);
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
                              (state_.f_ext_old[d] + state_.reaction_old[d] + state_.f_ext[d] +
                               state_.reaction_first[d]) *
                              state_.du[d]
                        : state_.f_ext[d] * (state_.positions[d] - state_.positions_settled[d]);
    const double friction =
        contact_ ? contact_->friction_work_between(state_.positions_settled, state_.positions)
                 : 0.0;
    energy_.add_snap_back(settled_energy - stored + work - friction);
  }
  std::swap(state_.positions, state_.positions_settled);
  return stored - (energy_.attempt_damage - released_before);
}

bool Simulation::prepare_next_pass(double mass_coefficient, bool grown) {
  changed_elements(model_, damage_before_, state_.changed_elements);
  const bool restraint_changed = hold_parts_cut_loose();
  const bool folded = !restraint_changed && grown && fold_modulus_change(mass_coefficient);
  prepare_system(mass_coefficient);  // nothing left to do once folded
  // The next solve's internal force at u_trial under the new moduli: bitwise what a full
  // recomputation gives (the same kernel per element, summed in the same order).
  ScopedTimer timer(timers_.assembly);
  refresh_element_forces(model_, state_.u_trial, state_.changed_elements,
                         state_.trial_element_force, corotational_);
  sum_element_forces(model_, coloring_, state_.trial_element_force, state_.f_int);
  return folded;
}

bool Simulation::increment_acceptable(long step, StepControl& control) {
  const std::size_t num_dofs = model_.X.size();
  double largest = 0.0;
  for (std::size_t d = 0; d < num_dofs; ++d) largest = std::max(largest, std::abs(state_.du[d]));
  if (!control.displacement_ok(largest)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "largest displacement increment %.3g m exceeds max_step_displacement", largest);
    control.reject(step, buf);
    return false;
  }
  // Contacts are found at the start of a step: a node that moves farther than the search
  // distance in one step may pass through a block unseen (DDA's maximum displacement rule).
  if (contact_ && !scene_.time.max_step_displacement && largest > contact_->parameters().reach) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "largest displacement increment %.3g m exceeds the contact search distance "
                  "%.3g m (time.max_step_displacement sets another limit)",
                  largest, contact_->parameters().reach);
    control.reject(step, buf);
    return false;
  }
  return true;
}

void Simulation::record_first_reaction() {
  // f_int at the solution is the damage check's (before this pass drops any modulus).
  const std::size_t num_dofs = model_.X.size();
  std::fill(state_.reaction_first.begin(), state_.reaction_first.end(), 0.0);
  if (contact_) {
    for (std::size_t d = 0; d < num_dofs; ++d)
      state_.positions[d] = model_.X[d] + model_.u[d] + state_.du[d];
    contact_->add_springs(state_.positions, layout_, model_.num_elements(), {},
                          state_.reaction_first);
  }
  for (std::size_t d = 0; d < num_dofs; ++d)
    state_.reaction_first[d] =
        constraint_force(bc_.prescribed[d], state_.damage_force[d], state_.reaction_first[d],
                         state_.restraint_force[d], state_.f_ext[d]);
}

DamageChange Simulation::evaluate_damage() {
  ScopedTimer timer(timers_.damage);
  const std::size_t num_dofs = model_.X.size();
  for (std::size_t d = 0; d < num_dofs; ++d) state_.positions[d] = model_.u[d] + state_.du[d];
  compute_internal_force(model_, coloring_, state_.positions, model_.strain, model_.stress,
                         state_.damage_force, corotational_);
  damage_before_ = model_.damage;
  const DamageChange change = damage_->evaluate(model_, scene_.fracture.damage_band);
  if (change.grown > 0) {
    factorized_mass_coefficient_ = -1.0;  // the moduli changed
    // Without carried velocity the pass drops the moduli at its own strain and re-solves from
    // there. A dynamic step instead integrates the whole step with the new moduli, from the
    // committed state: that is where its modulus drop takes the energy.
    energy_.attempt_damage += released_by_damage(
        damage_before_, analysis_ == Analysis::dynamic ? state_.committed_strain : model_.strain);
  }
  if (change.newly_damaged > 0 && !first_damage_ && !attempt_first_damage_) {
    FirstDamage first{stats_.steps + 1, attempt_time_, 0, 0.0, 0.0, 0.0};
    std::vector<std::array<double, 2>> centroids;
    for (std::int32_t e = 0; e < model_.num_elements(); ++e)
      if (model_.damage[e] > 0.0) centroids.push_back(reference_centroid(model_, e));
    first.elements = static_cast<std::int32_t>(centroids.size());
    for (const auto& c : centroids) {
      first.x += c[0] / first.elements;
      first.y += c[1] / first.elements;
    }
    for (const auto& c : centroids)
      first.spread = std::max(first.spread, std::hypot(c[0] - first.x, c[1] - first.y));
    attempt_first_damage_ = first;
  }
  return change;
}

bool Simulation::open_close_iteration(long step, int retries, const InertiaTerms& inertia,
                                      StepControl& control, bool factor_current) {
  const std::size_t num_dofs = model_.X.size();
  // The open-close iteration (a single solve without contacts): assume states, solve, check.
  const int limit = analysis_ == Analysis::dynamic ? kMaxOpenCloseIterations
                                                   : kMaxOpenCloseIterationsWithoutInertia;
  int iterations = 0;
  // factor_current: the factor already holds this iteration's system (springs switched by
  // updates in the last iteration, or moduli folded in by the last damage pass).
  while (true) {
    ++iterations;
    solve_iteration(step, inertia, factor_current);
    if (!contact_) break;
    double penetration = 0.0;
    int changes = 0;
    const std::vector<ContactSprings> before = contact_->springs();
    {
      ScopedTimer timer(timers_.contact);
      for (std::size_t d = 0; d < num_dofs; ++d)
        state_.positions[d] = model_.X[d] + model_.u[d] + state_.du[d];
      // Contacts that chatter near zero force are indeterminate, not wrong: past half the
      // iteration limit the tolerance doubles each iteration, up to 4x (kMaxRelaxationDoublings),
      // and the summary counts the steps that needed it.
      const int past = std::min(iterations - limit / 2, kMaxRelaxationDoublings);
      const double scale = past > 0 ? std::ldexp(1.0, past) : 1.0;
      // Last resort, in the closing iterations of a step already redone kRetriesBeforeSettling
      // times: contacts that keep swinging between two answers settle on their last one.
      const bool settle =
          retries >= kRetriesBeforeSettling && iterations > limit - kSettlingIterations;
      changes = contact_->update_states(state_.positions, scale, settle, penetration);
      if (changes == 0 && scale > 1.0) {
        ++stats_.open_close_relaxed_steps;
        stats_.largest_relaxation = std::max(stats_.largest_relaxation, scale);
      }
    }
    if (changes == 0) break;
    // Factor reuse: the springs that switched are a low-rank change of K. When updating the
    // factor is expected to cost less than refactorizing (docs/benchmarks.md), the
    // next iteration solves with the updated factor; a downdate that fails falls back.
    factor_current = false;
    if (bc_.num_equations > 0) {
      ScopedTimer timer(timers_.factorization);
      contact_->spring_changes(before, bc_.equation, springs_added_, springs_removed_);
      const std::int64_t columns = springs_added_.num_columns() + springs_removed_.num_columns();
      if (scene_.solver.factor_updates && solver_.update_expected_faster(columns)) {
        try {
          if (springs_added_.num_columns() > 0) solver_.update(springs_added_, true);
          if (springs_removed_.num_columns() > 0) solver_.update(springs_removed_, false);
          factor_current = true;
        } catch (const RunFailure&) {
          factor_current = false;  // refactorized from the springs in the next iteration
        }
      }
    }
    if (iterations >= limit) {
      stats_.open_close_iterations += iterations;
      control.reject(step, "the open-close iteration did not settle in " + std::to_string(limit) +
                               " iterations");
      return false;
    }
  }
  if (contact_) {
    stats_.open_close_iterations += iterations;
    stats_.max_open_close_per_step = std::max<long>(stats_.max_open_close_per_step, iterations);
  }
  return true;
}

bool Simulation::fold_modulus_change(double mass_coefficient) {
  if (!scene_.solver.factor_updates || bc_.num_equations == 0) return false;
  await_analysis();
  ScopedTimer timer(timers_.factorization);
  modulus_change_terms(model_, bc_.equation, state_.changed_elements, damage_before_, moduli_added_,
                       moduli_removed_);
  const std::int64_t columns = moduli_added_.num_columns() + moduli_removed_.num_columns();
  if (!solver_.update_expected_faster(columns)) return false;
  try {
    if (moduli_removed_.num_columns() > 0) solver_.update(moduli_removed_, false);
    if (moduli_added_.num_columns() > 0) solver_.update(moduli_added_, true);
  } catch (const RunFailure&) {
    return false;  // the factor is unusable: the caller reassembles and refactorizes
  }
  add_modulus_change(model_, layout_, state_.changed_elements, damage_before_,
                     contact_ ? base_values_ : values_);
  factorized_mass_coefficient_ = mass_coefficient;  // the values are current again
  values_incremental_ = true;
  ++stats_.folded_damage_passes;
  return true;
}

bool Simulation::hold_parts_cut_loose() {
  if (analysis_ == Analysis::dynamic) return false;  // inertia holds them
  const bool broke = std::any_of(
      state_.changed_elements.begin(), state_.changed_elements.end(),
      [&](std::int32_t e) { return damage_before_[e] < 1.0 && model_.damage[e] >= 1.0; });
  if (!broke) return false;
  FragmentRestraint held(model_, bc_, scene_.fracture.fragment_stiffness,
                         scene_.fracture.loose_part_support);
  if (held.same_springs(fragments_)) return false;
  held.anchor_new_springs(fragments_, state_.du);
  fragments_ = std::move(held);
  ++stats_.parts_cut_loose;
  loose_parts_held_ = true;
  // The springs act on the step's increment; the next solve starts again from u_trial.
  std::vector<double> trial_increment(model_.X.size());
  for (std::size_t d = 0; d < trial_increment.size(); ++d)
    trial_increment[d] = state_.u_trial[d] - model_.u[d];
  fragments_.forces(trial_increment, state_.restraint_force);
  factorized_mass_coefficient_ = -1.0;  // K takes the new springs
  return true;
}

void Simulation::solve_system() {
  double* x = state_.rhs.data();
  if (solver_.supernodal()) {  // a fresh factorization: as accurate as CHOLMOD makes it
    solver_.solve(x, x);
    return;
  }
  // The factor carries low-rank updates, whose round-off grows with each downdate: the
  // solution is checked against the assembled matrix by its normwise backward error
  // |b - A x| / (max|A| |x| + |b|), max norm (an SPD matrix's largest entry is on its
  // diagonal), and the matrix refactorized when that exceeds kTrusted. Iterative refinement
  // with the updated factor was tried and dropped: on the UCS, the disk and the sliding block
  // every solve was either already below 64 eps or did not improve in 30 refinements
  // (docs/benchmarks.md, "Damage passes folded into the factor", for the threshold's table).
  constexpr double kTrusted = 1e-10;
  const auto n = static_cast<std::size_t>(bc_.num_equations);
  check_rhs_.assign(x, x + n);
  check_residual_.resize(n);
  solver_.solve(x, x);
  const SparsityPattern& a = layout_.pattern;
  symmetric_residual(a, values_, {x, n}, check_rhs_, check_residual_);
  double largest_a = 0.0, largest_b = 0.0, largest_x = 0.0, residual = 0.0;
  for (std::int32_t j = 0; j < a.n; ++j)
    largest_a =
        std::max(largest_a, std::abs(values_[static_cast<std::size_t>(a.col_ptr[j + 1] - 1)]));
  for (std::size_t i = 0; i < n; ++i) {
    largest_b = std::max(largest_b, std::abs(check_rhs_[i]));
    largest_x = std::max(largest_x, std::abs(x[i]));
    residual = std::max(residual, std::abs(check_residual_[i]));
  }
  const double scale = largest_a * largest_x + largest_b;
  if (!(scale > 0.0) || residual <= kTrusted * scale) return;
  ++stats_.untrusted_updated_solves;
  {
    ScopedTimer timer(timers_.factorization);
    solver_.factorize(values_.data());
  }
  std::copy(check_rhs_.begin(), check_rhs_.end(), x);
  solver_.solve(x, x);
}

void Simulation::commit_step(double dt) {
  const std::size_t num_dofs = model_.X.size();
  energy_.integrator +=
      update_velocity(analysis_, integrator_, dt, state_.du, bc_.prescribed, bc_.velocity,
                      model_.node_mass, model_.v, state_.acceleration);
  if (corotational_) {
    // Only blocks that nothing holds turn exactly; the others stay where the solve balanced
    // them against their constraints and contacts.
    state_.held_nodes.assign(static_cast<std::size_t>(model_.num_nodes()), 0);
    for (std::size_t d = 0; d < num_dofs; ++d)
      if (bc_.prescribed[d]) state_.held_nodes[d / 2] = 1;
    if (contact_) contact_->mark_touching_nodes(state_.held_nodes);
    correct_block_rotations(model_, model_.u, state_.held_nodes, state_.du, model_.v,
                            state_.acceleration);
  }
  for (std::size_t d = 0; d < num_dofs; ++d) model_.u[d] += state_.du[d];
  {
    ScopedTimer timer(timers_.assembly);
    compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, state_.f_int,
                           corotational_);
  }
  if (contact_) {
    ScopedTimer timer(timers_.contact);
    for (std::size_t d = 0; d < num_dofs; ++d) state_.positions[d] = model_.X[d] + model_.u[d];
    // The step's contact forces before the commit folds the step's slip into the shear
    // springs' anchors: after it they would count that slip twice.
    std::fill(state_.f_contact.begin(), state_.f_contact.end(), 0.0);
    contact_->add_springs(state_.positions, layout_, model_.num_elements(), {}, state_.f_contact);
    contact_->commit(state_.positions);
  }
  fragments_.forces(state_.du, state_.restraint_force);
  // The restraint's springs restart from zero force next step: the energy they hold now
  // leaves the balance, a loss of the method (not of the rock) that summary.json reports.
  energy_.anchor += fragments_.energy(state_.du);
  // The constraints' force on the body, and the work of all external forces (trapezoidal).
  // Without inertia a damage cascade runs at fixed boundaries: the step's boundary work is
  // done at the first solve's reactions (record_first_reaction), not at the fallen ones.
  const bool first_reaction = damage_ && analysis_ != Analysis::dynamic;
  double work = 0.0;
  for (std::size_t d = 0; d < num_dofs; ++d) {
    state_.reaction[d] = constraint_force(bc_.prescribed[d], state_.f_int[d], state_.f_contact[d],
                                          state_.restraint_force[d], state_.f_ext[d]);
    const double reaction = first_reaction ? state_.reaction_first[d] : state_.reaction[d];
    work += 0.5 * (state_.f_ext_old[d] + state_.reaction_old[d] + state_.f_ext[d] + reaction) *
            state_.du[d];
  }
  energy_.external_work += work;
  if (damage_)  // where the next step's snap-back starts from, when it starts out of balance
    state_.committed_stored_energy = strain_energy(model_, model_.strain, model_.stress) +
                                     (contact_ ? contact_->spring_energy() : 0.0);
  state_.start_out_of_balance = state_.end_out_of_balance;
  std::swap(state_.f_ext_old, state_.f_ext);
  std::swap(state_.reaction_old, state_.reaction);
}

void Simulation::detach_fractured_elements() {
  ScopedTimer timer(timers_.damage);
  std::vector<double> threshold(static_cast<std::size_t>(model_.num_elements()));
  for (std::int32_t e = 0; e < model_.num_elements(); ++e)
    threshold[e] = damage_->detach_threshold(model_, e);
  if (edges_.neighbor.size() != model_.conn.size())
    edges_ = build_edge_adjacency(model_.conn, "fracture");
  const Detachment detachment = detach_damaged_elements(model_, threshold, detached_, edges_);
  if (detachment.detached == 0) return;
  stats_.detached_elements += detachment.detached;
  state_.start_out_of_balance = true;
  // Everything built on the nodes follows the split: the step state, the constraints and
  // loads (named curves carried their element sides over), probes, colouring and contacts.
  state_.follow_split_nodes(detachment.node_origin);
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
                    stats_.steps + 1, free->block, free->elements, free->body.c_str(),
                    free->motion.c_str());
      throw RunFailure(buf);
    }
  reference_loads_ = build_reference_loads(scene_, model_);
  state_.rhs.assign(static_cast<std::size_t>(bc_.num_equations), 0.0);
  auto probes = std::make_unique<Probes>(scene_, model_);
  probes->carry_state_from(*probes_);
  probes_ = std::move(probes);
  coloring_ = color_elements(model_.conn, model_.num_nodes());
  if (analysis_ != Analysis::dynamic)
    fragments_ = FragmentRestraint(model_, bc_, scene_.fracture.fragment_stiffness,
                                   scene_.fracture.loose_part_support);
  loose_parts_held_ = false;
  if (analysis_ != Analysis::dynamic && corotational_) turn_loose_block_frames();
  auto contact = std::make_unique<ContactStage>(scene_, model_, analysis_);
  if (contact_) contact->carry_contacts_from(*contact_);
  contact_ = std::move(contact);
  rebuild_layout();
  recompute_committed_forces();
}

void Simulation::follow_cascade_with_inertia(long step, double time, double end_time,
                                             StepControl& control) {
  inertia_called_for_ = false;
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
  inertia_switch_ = InertiaSwitch{step, time, dt};
  // Inertia holds loose blocks now; contacts lose the sliding springs of steps without it.
  fragments_ = FragmentRestraint();
  loose_parts_held_ = false;
  std::fill(state_.restraint_force.begin(), state_.restraint_force.end(), 0.0);
  if (contact_) contact_->set_analysis(analysis_);  // same contacts, same pattern
  factorized_mass_coefficient_ = -1.0;
  // The last pass's modulus drop left the committed state out of balance.
  balance_acceleration();
}

void Simulation::balance_acceleration() {
  // Starting from a = 0 instead would misplace every later velocity by the unbalanced force
  // (g dt / 2 for a body under gravity at rest).
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    state_.acceleration[d] = bc_.prescribed[d] || analysis_ != Analysis::dynamic
                                 ? 0.0
                                 : (state_.f_ext_old[d] - state_.f_int[d] - state_.f_contact[d]) /
                                       model_.node_mass[d / 2];
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
  compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, state_.f_int,
                         corotational_);
  std::fill(state_.f_contact.begin(), state_.f_contact.end(), 0.0);
  for (std::size_t d = 0; d < num_dofs; ++d) state_.positions[d] = model_.X[d] + model_.u[d];
  contact_->add_committed_forces(state_.positions, state_.f_contact);
  fragments_.forces(state_.du, state_.restraint_force);
  for (std::size_t d = 0; d < num_dofs; ++d) {
    state_.f_ext_old[d] = state_.load_factor * reference_loads_[d];
    state_.reaction_old[d] =
        constraint_force(bc_.prescribed[d], state_.f_int[d], state_.f_contact[d],
                         state_.restraint_force[d], state_.f_ext_old[d]);
  }
}

bool Simulation::Softening::observe(long at_step, double at_time, double v, double drop) {
  step = at_step;
  time = at_time;
  value = v;
  if (std::abs(v) > peak) {
    peak = std::abs(v);
    peak_step = at_step;
    peak_time = at_time;
  }
  reached = peak > 0.0 && std::abs(v) <= (1.0 - drop) * peak;
  return reached;
}

nlohmann::json Simulation::Softening::summary(const TimeSpec& spec) const {
  return {{"probe", spec.softening_probe},
          {"fraction", *spec.stop_at_softening},
          {"peak", peak},
          {"peak_step", peak_step},
          {"peak_time", peak_time},
          {"reached", reached},
          {"step", step},
          {"time", time},
          {"value", value}};
}

double Simulation::released_by_damage(std::span<const double> damage_before,
                                      std::span<const double> strain) const {
  // At `strain`, where the modulus drops; the deformation the softer element takes on
  // afterwards is stored at the new modulus (counted in the strain energy). Serially in
  // element order: the total must not depend on threads.
  const kernels::PlaneKind plane = plane_kind(model_.plane);
  double energy = 0.0;
  for (std::int32_t e = 0; e < model_.num_elements(); ++e)
    if (model_.damage[e] > damage_before[e])
      energy += kernels::damage_dissipation(
                    &strain[3 * static_cast<std::size_t>(e)], model_.young[e], model_.poisson[e],
                    plane, damage_before[e], model_.damage[e], kDamagedStiffnessFloor) *
                model_.area0[e];
  return energy * model_.thickness;
}

double Simulation::stored_energy() {
  // The mass term c M of a quasi-static step is not stored: it holds the step's motion, which
  // the next step starts without (the velocity reset), so what goes into it is released.
  const std::size_t num_dofs = model_.X.size();
  for (std::size_t d = 0; d < num_dofs; ++d)
    state_.positions[d] = model_.X[d] + model_.u[d] + state_.du[d];
  double energy =
      strain_energy(model_, model_.strain, model_.stress) + fragments_.energy(state_.du);
  if (contact_) energy += contact_->spring_energy_at(state_.positions);
  return energy;
}

double Simulation::element_force_scale() const {
  // The largest force an element edge carries, about |sigma| sqrt(2 A) t, and the largest
  // load or reaction on a node.
  double scale = 0.0;
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    scale = std::max({scale, std::abs(state_.reaction_old[d]), std::abs(state_.f_ext_old[d])});
  for (std::int32_t e = 0; e < model_.num_elements(); ++e) {
    const double* sigma = &model_.stress[3 * static_cast<std::size_t>(e)];
    const double largest = std::max({std::abs(sigma[0]), std::abs(sigma[1]), std::abs(sigma[2])});
    scale = std::max(scale, largest * std::sqrt(2.0 * model_.area0[e]) * model_.thickness);
  }
  return scale;
}

EnergyBalance Simulation::energy() const {
  EnergyBalance e;
  for (std::int32_t n = 0; n < model_.num_nodes(); ++n)
    e.kinetic += 0.5 * model_.node_mass[n] *
                 (model_.v[2 * n] * model_.v[2 * n] + model_.v[2 * n + 1] * model_.v[2 * n + 1]);
  e.strain = strain_energy(model_, model_.strain, model_.stress) +
             (contact_ ? contact_->spring_energy() : 0.0);
  e.external_work = energy_.external_work;
  e.dissipated = energy_.damage + (contact_ ? contact_->friction_dissipation() : 0.0);
  e.snap_back = energy_.snap_back;
  e.integrator = energy_.integrator;
  return e;
}

void Simulation::evaluate_probes(std::vector<double>& row) {
  row.clear();
  // After commit_step the newest reaction sits in state_.reaction_old.
  probes_->evaluate(model_, state_.reaction_old, row);
}

RunResult Simulation::run(const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));

  const double end_time = end_time_of(scene_);
  StepControl control(scene_.time);
  std::unique_ptr<RunOutputs> outputs;
  if (options.write_outputs)
    outputs = std::make_unique<RunOutputs>(scene_, run_folder(scene_, options), probes_->columns(),
                                           probes_->has_line_probes(), options.write_frames);

  // Step 0: the initial state.
  const double initial_factor = load_factor(analysis_, 0.0, end_time);
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    state_.f_ext_old[d] = initial_factor * reference_loads_[d];
  compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, state_.f_int,
                         corotational_);
  balance_acceleration();  // no contact force yet: f_contact is zero
  std::vector<double> row;
  // The end on softening (time.stop_at_softening) watches one history column.
  const bool watch_softening = scene_.time.stop_at_softening.has_value();
  const auto& columns = probes_->columns();
  const std::size_t softening_column =
      watch_softening ? static_cast<std::size_t>(
                            std::find(columns.begin(), columns.end(), scene_.time.softening_probe) -
                            columns.begin())
                      : 0;
  auto record = [&](long step, double time, double dt, bool last) {
    if (!outputs && !watch_softening) return last;
    ScopedTimer timer(timers_.output);
    evaluate_probes(row);
    if (watch_softening &&
        softening_.observe(step, time, row[softening_column], *scene_.time.stop_at_softening))
      last = true;
    if (!outputs) return last;
    outputs->history_row(step, time, dt, row, energy());
    const int every = scene_.output.every;
    if (last || (every > 0 && step % every == 0)) {
      outputs->frame(model_, step, time);
      probes_->write_profiles(model_, outputs->dir() / "profiles", step);
    }
    return last;
  };
  record(0, 0.0, control.dt(), false);

  RunResult result;
  double t = 0.0;
  bool frame_written = false;      // the failing step's frame is already out
  bool stopped_by_caller = false;  // options.keep_going said false
  const long planned = std::lround(end_time / scene_.time.dt);
  try {
    while (t < end_time * (1.0 - 1e-12)) {
      const long step = stats_.steps + 1;
      double dt = control.step_to(end_time - t);
      attempt_time_ = t + dt;
      for (int retries = 0;
           !attempt_step(step, retries, dt, load_factor(analysis_, t + dt, end_time), control);
           ++retries) {
        ++stats_.redone_steps;
        dt = control.step_to(end_time - t);
        attempt_time_ = t + dt;
      }
      commit_step(dt);
      if (damage_) {
        energy_.commit_attempt();
        committed_damage_ = model_.damage;
        if (!first_damage_) first_damage_ = attempt_first_damage_;
      }
      // A detachment that ends the run (a static specimen that failed) still leaves the
      // committed step in history.csv and its frame.
      std::optional<RunFailure> fracture_failure;
      try {
        if (damage_) detach_fractured_elements();
      } catch (const RunFailure& failure) {
        fracture_failure = failure;
      }
      t += dt;
      stats_.steps = step;
      control.accept(true);
      const StepReport report{step, t, dt, end_time, planned};
      if (!fracture_failure && options.keep_going && !options.keep_going(report, model_))
        stopped_by_caller = true;
      const bool last = t >= end_time * (1.0 - 1e-12) || stopped_by_caller;
      const bool stop = record(step, t, dt, last || fracture_failure.has_value());
      if (fracture_failure) {
        frame_written = true;
        throw *fracture_failure;
      }
      if (options.on_step) options.on_step(report, model_);
      if (stop) break;
      if (inertia_called_for_) follow_cascade_with_inertia(step, t, end_time, control);
    }
  } catch (const RunFailure& failure) {
    result.ok = false;
    result.reason = failure.what();
    if (outputs && !frame_written) {
      ScopedTimer timer(timers_.output);
      outputs->frame(model_, stats_.steps, t);  // the last committed state, for diagnosis
    }
  }
  try {
    await_analysis();  // the summary reads the solver
  } catch (const std::exception& failure) {
    if (result.ok) {
      result.ok = false;
      result.reason = failure.what();
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.summary = summary(result, wall, threads, options.setup);
  result.summary["dt_changes"] = control.changes();
  if (watch_softening) result.summary["softening"] = softening_.summary(scene_.time);
  if (stopped_by_caller) result.summary["stopped_by_caller"] = true;
  if (outputs) {
    for (const auto& [column, peak] : outputs->peaks()) result.summary["peaks"][column] = peak;
    outputs->finish(result.summary);
  }
  return result;
}

nlohmann::json Simulation::timers_summary(double wall_seconds,
                                          const std::optional<SetupReport>& setup) const {
  nlohmann::json t = {{"assembly", timers_.assembly},
                      {"factorization", timers_.factorization},
                      {"solve", timers_.solve},
                      {"contact", timers_.contact},
                      {"damage", timers_.damage},
                      {"output", timers_.output},
                      {"layout", timers_.layout},
                      {"analysis", timers_.analysis},
                      {"step_other", std::max(0.0, wall_seconds - timers_.sum())},
                      {"setup_layout", setup_timers_.layout},
                      {"setup_analysis", setup_timers_.analysis},
                      {"setup", setup_timers_.other}};
  if (!setup) return t;
  double named = setup->scene + setup->meshing + setup->model + setup_timers_.sum() + wall_seconds;
  if (setup->startup) {
    t["startup"] = *setup->startup;
    named += *setup->startup;
  }
  t["scene"] = setup->scene;
  t["meshing"] = setup->meshing;
  t["model"] = setup->model;
  // The process's age when the summary is made; what the named timers miss is the gaps
  // between them (and /proc's 10 ms resolution of the process's start).
  if (const std::optional<double> process = process_age_seconds(); process && setup->startup) {
    t["process"] = *process;
    t["unaccounted"] = *process - named;
  }
  return t;
}

nlohmann::json Simulation::summary(const RunResult& result, double wall_seconds, int threads,
                                   const std::optional<SetupReport>& setup) const {
  nlohmann::json s;
  s["scene"] = scene_.name;
  s["status"] = result.ok ? "ok" : "failed";
  if (!result.ok) s["reason"] = result.reason;
  s["rockdd_version"] = ROCKDD_VERSION;
  s["threads"] = threads;
  s["wall_seconds"] = wall_seconds;
  s["analysis"] = analysis_name(scene_.analysis);  // as the scene gives it
  stats_.write(s);
  s["open_close_shear_swings_settled"] = contact_ ? contact_->shear_swings_settled() : 0;
  s["open_close_normal_swings_settled"] = contact_ ? contact_->normal_swings_settled() : 0;
  s["elements"] = model_.num_elements();
  s["nodes"] = model_.num_nodes();
  s["equations"] = bc_.num_equations;
  s["blocks"] = model_.num_blocks;
  if (damage_) {
    // METHOD.md: say which tensile onset each damageable material uses.
    nlohmann::json onset = nlohmann::json::object();
    for (std::size_t i = 0; i < scene_.materials.size(); ++i)
      if (scene_.materials[i].has_damage())
        onset["material[" + std::to_string(i) + "]"] =
            scene_.materials[i].tension_onset == TensionOnset::strain ? "strain" : "stress";
    s["tension_onset"] = onset;
    if (first_damage_)
      s["first_damage"] = {{"step", first_damage_->step},
                           {"time", first_damage_->time},
                           {"elements", first_damage_->elements},
                           {"x", first_damage_->x},
                           {"y", first_damage_->y},
                           {"spread", first_damage_->spread}};
    else
      s["first_damage"] = nullptr;
    if (scene_.fracture.snap_back == FractureSpec::SnapBack::dynamic)
      s["snap_back_inertia"] = inertia_switch_ ? nlohmann::json{{"step", inertia_switch_->step},
                                                                {"time", inertia_switch_->time},
                                                                {"dt", inertia_switch_->dt}}
                                               : nlohmann::json(nullptr);
  }
  {
    // The balance of the last committed state, split by where the work went; what is left
    // over measures the scheme's own losses (contact reset, step relinearisation).
    const EnergyBalance e = energy();
    const double friction = contact_ ? contact_->friction_dissipation() : 0.0;
    s["energy"] = {{"external_work", e.external_work},
                   {"kinetic", e.kinetic},
                   {"strain", e.strain},
                   {"damage_dissipation", energy_.damage},
                   {"friction_dissipation", friction},
                   {"snap_back", energy_.snap_back},
                   {"created_by_resolves", energy_.created},
                   {"anchor_work", energy_.anchor},
                   {"integrator_dissipation", energy_.integrator},
                   {"unaccounted", e.external_work - e.kinetic - e.strain - e.dissipated -
                                       e.snap_back - energy_.anchor - e.integrator}};
  }
  s["damaged_elements"] =
      std::count_if(model_.damage.begin(), model_.damage.end(), [](double w) { return w > 0; });
  s["peaks"] = nlohmann::json::object();
  nlohmann::json defaults = nlohmann::json::object();
  for (const auto& [key, value] : scene_.defaults) defaults[key] = value;
  defaults["mass"] = "lumped";
  if (contact_) {
    defaults["contact.normal_stiffness"] = contact_->parameters().normal_stiffness;
    defaults["contact.shear_stiffness"] = contact_->parameters().shear_stiffness;
    defaults["contact.reach"] = contact_->parameters().reach;
    if (!scene_.time.max_step_displacement)
      defaults["time.max_step_displacement"] = contact_->parameters().reach;
  }
  s["defaults"] = defaults;
  s["timers"] = timers_summary(wall_seconds, setup);
  if (setup) s["mesh_cache"] = mesh_cache_outcome_name(setup->mesh_cache);
  const SolverStats& st = solver_.stats();
  s["solver"] = {{"analyses", st.analyses},
                 {"analysis_seconds", st.analysis_seconds},
                 {"factorizations", st.factorizations},
                 {"updates", st.updates},
                 {"updated_columns", st.updated_columns},
                 {"nonzeros", layout_.pattern.nnz()},
                 {"ordering", std::string(fill_ordering_name(st.ordering))},
                 {"ordering_cache", mesh_cache_outcome_name(ordering_cache_)},
                 {"factor_nonzeros", st.factor_nonzeros},
                 {"factor_flops", st.last_factor_flops}};
  return s;
}

}  // namespace rockdd

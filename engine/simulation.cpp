#include "engine/simulation.hpp"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/assembly/internal_force.hpp"
#include "engine/common/errors.hpp"
#include "engine/contact/contact_stage.hpp"
#include "engine/damage/damage_stage.hpp"
#include "engine/damage/disintegration.hpp"
#include "engine/damage/load_path.hpp"
#include "engine/loading/external_loads.hpp"
#include "engine/loading/initial_motion.hpp"
#include "engine/output/probes.hpp"
#include "engine/output/run_outputs.hpp"
#include "engine/report/run_result.hpp"
#include "engine/report/run_summary.hpp"
#include "engine/solver/linear_system.hpp"
#include "engine/time/energy_check.hpp"
#include "engine/time/integrator.hpp"
#include "engine/time/onset_cuts.hpp"
#include "engine/time/rotation_correction.hpp"
#include "engine/time/snap_back.hpp"
#include "engine/time/step_control.hpp"

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
/// Newton corrections of a solve whose elements turned past kFrameTolerance (each follows the
/// frames again).
constexpr int kMaxFrameCorrections = 4;

/// The onset ratio above which a step counts as having passed an onset: an onset is located to
/// within what the state is known to, the damage band and the growth tolerance to which a
/// step's moduli settle.
double onset_tolerance(const FractureSpec& fracture) {
  return 1.0 + std::max(fracture.damage_band, fracture.growth_tolerance);
}

/// The onset ratio a step that passed an onset is cut back to: half way into the tolerance.
double onset_target(const FractureSpec& fracture) {
  return 0.5 * (1.0 + onset_tolerance(fracture));
}

/// Run length: `end`, or `steps` x dt, or one step of 1 s in a static scene without [time].
double end_time_of(const Scene& scene) {
  if (scene.time.end) return *scene.time.end;
  return static_cast<double>(scene.time.steps.value_or(1)) * scene.time.dt;
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
      energy_check_(scene_.time.energy_tolerance),
      system_(std::make_unique<LinearSystem>(report_.timers, std::move(mesh_slot),
                                             scene_.solver.factor_updates)) {
  ScopedTimer timer(report_.setup_timers.other);
  // Blocks that move turn: their strain is measured in co-rotated frames. A static analysis
  // restrains every block and solves once, small strain (f_int = K u exactly).
  corotational_ = analysis_ != Analysis::static_;
  bc_ = build_boundary_conditions(scene_, model_);
  if (analysis_ == Analysis::static_) check_static_restraint(scene_, model_, bc_);
  reference_loads_ = build_reference_loads(scene_, model_);
  probes_ = std::make_unique<Probes>(scene_, model_);
  {
    ScopedTimer layout_timer(report_.timers.layout);
    coloring_ = color_elements(model_.conn, model_.num_nodes());
  }
  if (!scene_.joints.empty())
    contact_ = std::make_unique<ContactStage>(scene_, model_, analysis_, integrator_);
  if (!model_.tensile_strength.empty()) damage_ = std::make_unique<DamageStage>(scene_, model_);
  watch_disintegration_ = damage_ && analysis_ == Analysis::quasi_static &&
                          fracturing_block_spread(model_).largest_share >= kFragmentShare;
  watch_load_path_ = watch_disintegration_ && has_load_path_boundaries(bc_);
  rebuild_layout();
  // The step loop's timers start at zero: what the first layout took is set-up.
  std::swap(report_.setup_timers.layout, report_.timers.layout);
  std::swap(report_.setup_timers.analysis, report_.timers.analysis);
  trial_.resize(model_.X.size(), bc_.num_equations);
  committed_.resize(model_.X.size());
  apply_initial_motion(scene_, model_);
}

Simulation::~Simulation() = default;

const SolverStats& Simulation::solver_stats() const {
  return system_->solver_stats();
}

void Simulation::rebuild_layout() {
  std::vector<std::int32_t> conn = model_.conn;
  if (contact_) {
    const std::vector<std::int32_t> triples = contact_->triples();
    conn.insert(conn.end(), triples.begin(), triples.end());
  }
  // A static analysis without damage or contact factorizes once: its ordering should cost
  // little next to that one factorization.
  const bool factorized_once = analysis_ == Analysis::static_ && !damage_ && !contact_;
  system_->rebuild(conn, model_.num_nodes(), bc_.equation, bc_.num_equations, contact_ != nullptr,
                   {model_.X, factorized_once ? OrderingEffort::quick : OrderingEffort::thorough});
}

void Simulation::prepare_system(double mass_coefficient) {
  system_->prepare(model_, coloring_, bc_.equation, mass_coefficient,
                   {fragments_.dofs(), fragments_.stiffness()});
}

RunResult Simulation::run(const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));

  const double end_time = end_time_of(scene_);
  on_attempt_ = options.on_attempt;
  StepControl control(scene_.time);
  std::unique_ptr<RunOutputs> outputs;
  if (options.write_outputs)
    outputs = std::make_unique<RunOutputs>(scene_, run_folder(scene_, options), probes_->columns(),
                                           probes_->has_line_probes(), options.write_frames);

  // Step 0: the initial state.
  committed_.load_factor = load_factor(analysis_, 0.0, end_time);
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    committed_.f_ext[d] = committed_.load_factor * reference_loads_[d];
  committed_.element_force.resize(6 * static_cast<std::size_t>(model_.num_elements()));
  compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, trial_.f_int,
                         corotational_, committed_.element_force);
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    committed_.residual[d] = bc_.prescribed[d] ? 0.0 : committed_.f_ext[d] - trial_.f_int[d];
  balance_acceleration();  // no contact force yet: f_contact is zero
  record_committed_state(false);
  {
    const EnergyBalance at_start = energy();
    committed_.energy.initial = at_start.kinetic + at_start.strain;
  }
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
    ScopedTimer timer(report_.timers.output);
    row.clear();
    probes_->evaluate(model_, committed_.reaction, row);
    if (watch_softening && report_.softening.observe(step, time, row[softening_column],
                                                     *scene_.time.stop_at_softening))
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
  bool onset_damage_next = false;  // the last step ended at an onset: its damage runs now
  bool stood = false;  // the last step had no length and located no onset: it settled one
  const long planned = std::lround(end_time / scene_.time.dt);
  RunStats& counters = report_.counters;
  try {
    while (t < end_time * (1.0 - 1e-12)) {
      const long step = counters.steps + 1;
      double dt = onset_damage_next ? 0.0 : control.step_to(end_time - t);
      OnsetCuts cuts(onset_target(scene_.fracture), !stood);
      const EnergyBalance balance_before = energy();  // of the committed state
      energy_check_.begin_step();
      for (int retries = 0;;) {
        const Attempt attempt =
            attempt_step(step, retries, t, dt, load_factor(analysis_, t + dt, end_time), control,
                         cuts, onset_damage_next);
        if (attempt == Attempt::accepted) {
          if (commit_checked_step(step, dt, balance_before, control)) break;
        } else if (attempt == Attempt::cut_at_onset) {
          dt = cuts.next(dt, trial_.onset_fraction, trial_.onset_largest, trial_.damage_passes > 0);
          ++counters.onset_cuts;
          continue;
        }
        ++retries;
        ++counters.redone_steps;
        dt = control.step_to(end_time - t);
      }
      stood = dt == 0.0 && !onset_damage_next;
      onset_damage_next = trial_.onset_located;
      if (onset_damage_next) {
        ++counters.located_onsets;
        control.restart_growth();
      }
      for (EventState& state : trial_.events) {
        if (outputs) state.event.frame = outputs->event_frame(state.model, state.event.name);
        if (options.on_event) options.on_event(state.event, state.model);
        committed_.events.push_back(std::move(state.event));
      }
      trial_.events.clear();
      // A detachment that ends the run (a static specimen that failed) still leaves the
      // committed step in history.csv and its frame.
      std::optional<RunFailure> fracture_failure;
      // Whether the step's solution still joins the moving boundary to a held one, before its
      // broken elements are detached (their crack faces have no contacts solved yet).
      const bool carried = !watch_load_path_ || carries_load();
      bool detached = false;
      try {
        if (damage_) detached = detach_fractured_elements();
      } catch (const RunFailure& failure) {
        fracture_failure = failure;
      }
      record_committed_state(detached);
      t += dt;
      counters.steps = step;
      // Loose fragments have no quasi-static equilibrium: only the restraint and the mass
      // term would hold them, so the balance could not close. The answer is the run so far.
      if (detached && watch_disintegration_ && analysis_ == Analysis::quasi_static)
        if (const BlockSpread spread = fracturing_block_spread(model_);
            spread.largest_share < kFragmentShare)
          report_.disintegration = Disintegration{step, t, spread, DisintegrationCause::fragments};
      // Blocks that nothing joins to both boundaries have no equilibrium either: whatever they
      // carry goes into the restraint, and their fragments crawl at the displacement check's dt.
      if (!carried && !report_.disintegration && analysis_ == Analysis::quasi_static)
        report_.disintegration = Disintegration{step, t, fracturing_block_spread(model_),
                                                DisintegrationCause::no_load_path};
      // A step that ends at no onset lets a shortened dt grow back to the scene's. Where onsets
      // are located it may have damaged: onsets and growth do not follow the step's length
      // there, and a run past its peak, which damages in nearly every step, would otherwise
      // stay at the dt of its worst rejection. A quiet one (nothing damaged, no contact
      // switched) lets dt grow past the scene's, up to dt_max. The next located onset takes
      // dt back to the scene's.
      if (dt > 0.0) {
        const bool located = scene_.fracture.locate_onsets && analysis_ != Analysis::dynamic;
        const bool easy = !onset_damage_next && (located || !trial_.damage_changed);
        control.accept(easy, easy && !trial_.damage_changed && !trial_.contact_changed);
      }
      const StepReport report{step, t, dt, end_time, planned};
      if (!fracture_failure && options.keep_going && !options.keep_going(report, model_))
        report_.stopped_by_caller = true;
      const bool last = t >= end_time * (1.0 - 1e-12) || report_.stopped_by_caller ||
                        report_.disintegration.has_value();
      const bool stop = record(step, t, dt, last || fracture_failure.has_value());
      if (fracture_failure) {
        frame_written = true;
        throw *fracture_failure;
      }
      if (options.on_step) options.on_step(report, model_);
      if (stop) break;
      if (trial_.calls_for_inertia) follow_cascade_with_inertia(step, t, end_time, control);
    }
  } catch (const RunFailure& failure) {
    result.ok = false;
    result.reason = failure.what();
    if (outputs && !frame_written) {
      ScopedTimer timer(report_.timers.output);
      outputs->frame(model_, counters.steps, t);  // the last committed state, for diagnosis
    }
  }
  try {
    system_->await_analysis();  // the summary reads the solver
  } catch (const std::exception& failure) {
    if (result.ok) {
      result.ok = false;
      result.reason = failure.what();
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  counters.dt_changes = control.changes();
  result.summary =
      run_summary({scene_, model_, report_, committed_, energy(), contact_.get(), *system_,
                   bc_.num_equations, result.ok, result.reason, wall, threads, options.setup,
                   energy_check_});
  if (outputs) {
    for (const auto& [column, peak] : outputs->peaks()) result.summary["peaks"][column] = peak;
    outputs->finish(result.summary);
  }
  return result;
}

void Simulation::begin_attempt(double time, double load_factor) {
  trial_.begin_attempt(time, load_factor);
  // Whatever a rejected attempt left in the model's working fields and the restraint.
  model_.strain = committed_.strain;
  model_.stress = committed_.stress;
  if (!damage_) return;
  model_.damage = committed_.damage;         // the system follows it back (LinearSystem::prepare)
  if (fragments_ != committed_.restraint) {  // springs or anchors
    if (!fragments_.same_springs(committed_.restraint)) system_->invalidate();
    fragments_ = committed_.restraint;
  }
}

double Simulation::inertia_step(double dt, const StepControl& control) const {
  return analysis_ == Analysis::quasi_static ? std::min(scene_.time.dt, control.dt()) : dt;
}

Simulation::Attempt Simulation::attempt_step(long step, int retries, double time, double dt,
                                             double load_factor, StepControl& control,
                                             const OnsetCuts& cuts, bool onset_at_start) {
  const std::size_t num_dofs = model_.X.size();
  begin_attempt(time + dt, load_factor);
  if (on_attempt_) on_attempt_(AttemptReport{step, retries, dt}, model_);
  if (contact_) {
    bool changed = false;
    {
      ScopedTimer timer(report_.timers.contact);
      for (std::size_t d = 0; d < num_dofs; ++d) trial_.positions[d] = model_.X[d] + model_.u[d];
      changed = contact_->detect(trial_.positions, committed_.contacts);
    }
    if (changed) rebuild_layout();
    if (analysis_ != Analysis::dynamic)
      contact_->set_force_scale(contact_force_scale(model_, committed_.reaction, committed_.f_ext));
  }
  // Co-rotation: the stiffness follows the elements' frames once any has turned by more than
  // kFrameTolerance since K was assembled (the internal force always uses the exact frames).
  if (corotational_ && frames_turned_past(model_, model_.u, kFrameTolerance)) {
    update_element_rotations(model_, model_.u);
    system_->invalidate();
  }
  const InertiaTerms inertia = inertia_terms(analysis_, integrator_, inertia_step(dt, control));
  prepare_system(inertia.mass_coefficient);

  for (std::size_t d = 0; d < num_dofs; ++d) {
    trial_.du[d] = bc_.prescribed[d] ? bc_.velocity[d] * dt : 0.0;
    trial_.u_trial[d] = model_.u[d] + trial_.du[d];
    trial_.f_ext[d] = load_factor * reference_loads_[d];
  }
  {
    ScopedTimer timer(report_.timers.assembly);
    // Each element's force is kept: a damage pass recomputes only the elements it changed.
    // The committed state's forces hold at u for every element the prescribed increment does
    // not move (the attempt starts from its strain and stress): only the others are computed,
    // by the same kernel, and the sum runs in the same order, so f_int is bitwise what a whole
    // pass gives.
    const std::size_t element_values = 6 * static_cast<std::size_t>(model_.num_elements());
    if (committed_.element_force.size() == element_values) {
      trial_.trial_element_force = committed_.element_force;
      elements_moved_between(model_, model_.u, trial_.u_trial, trial_.moved_nodes,
                             trial_.moved_elements);
      refresh_element_forces(model_, trial_.u_trial, trial_.moved_elements,
                             trial_.trial_element_force, corotational_, model_.strain,
                             model_.stress);
      sum_element_forces(model_, coloring_, trial_.trial_element_force, trial_.f_int);
    } else {
      trial_.trial_element_force.resize(element_values);
      compute_internal_force(model_, coloring_, trial_.u_trial, model_.strain, model_.stress,
                             trial_.f_int, corotational_, trial_.trial_element_force);
    }
    for (std::size_t d = 0; d < num_dofs; ++d) trial_.du[d] = trial_.u_trial[d] - model_.u[d];
    fragments_.forces(trial_.du, trial_.restraint_force);
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
  const bool settle_start = count_snap_back && damage_ && committed_.out_of_balance;
  double settled_energy = 0.0;  // stored energy just after the last pass dropped the moduli
  if (settle_start) {
    settled_energy = committed_.stored_energy;
    for (std::size_t d = 0; d < num_dofs; ++d)
      trial_.positions_settled[d] = model_.X[d] + model_.u[d];
  }
  // Onsets are located in steps without inertia (with inertia the step follows the waves):
  // a step whose first solve carries an undamaged element past its onset by more than the
  // damage band is cut back to where the first one reaches it (within the band), and a step
  // that ends there commits without damage; the next step, of no length, runs that damage at
  // the same displacement. So the state at the onset is a history row, and no damage runs at
  // a displacement that only the step's length chose.
  // While onsets are located, a pass grows the damage of elements already damaged but starts
  // none; once that growth has settled, the onsets are sought in the settled state.
  const bool locate_onsets = scene_.fracture.locate_onsets && analysis_ != Analysis::dynamic &&
                             (dt > 0.0 || cuts.locates_at_no_length());
  const bool may_cut = cuts.may_cut();
  // The damage of an onset the last step located runs where it was located: from the
  // committed state, before any solve (which would first settle the growth that step left).
  const bool located_onset_damage = damage_ && onset_at_start;
  for (int pass = 1;; ++pass) {
    const bool solved = !(pass == 1 && located_onset_damage);
    if (solved && !open_close_iteration(step, retries, inertia, &control)) return Attempt::rejected;
    if (solved && !follow_turned_frames(step, retries, inertia, control)) return Attempt::rejected;
    // A settling or cascading solve moves parts by what the rock released, not by what the
    // step's length chose: the restraint's springs let them go where that takes them.
    if (solved && count_snap_back && damage_ && (pass > 1 || settle_start))
      relax_restraint(step, retries, inertia, control);
    // Without inertia the first solve ends balanced against its mass term c M du, not at rest,
    // and starts from the committed state's imbalance: the work of both over du (trapezoidal)
    // is what the loads did beyond what the body stores, which a dynamic run would turn into
    // motion and the velocity reset discards. The scheme's own loss, booked by name; the
    // passes after it, and a first solve that settles damage, book theirs as snap-back.
    if (pass == 1 && analysis_ == Analysis::quasi_static && !settle_start) {
      double imbalance_work = 0.0;
      for (std::size_t d = 0; d < num_dofs; ++d)
        imbalance_work += committed_.residual[d] * trial_.du[d];
      trial_.energy.quasi_static =
          mass_term_energy(inertia.mass_coefficient, trial_.du, bc_.prescribed, model_.node_mass) +
          0.5 * imbalance_work;
    }
    if (!damage_) break;
    const double released_before = trial_.energy.damage;
    strain_at_result();
    // Softening of elements already damaged only loads the others further: an onset that the
    // first solve passes already is cut back to at once, before any growth is settled.
    if (pass == 1 && locate_onsets && may_cut) {
      const OnsetSearch onset = locate_onset(onset_target(scene_.fracture));
      if (onset.largest > onset_tolerance(scene_.fracture) && onset.fraction) {
        trial_.onset_fraction = *onset.fraction;
        trial_.onset_largest = onset.largest;
        return Attempt::cut_at_onset;
      }
    }
    const DamageChange change = evaluate_damage(!locate_onsets);
    // Without inertia the boundaries move in the first solve only; the cascade after it runs
    // at fixed boundaries, so the step's work is done at the first solve's reactions.
    if (pass == 1 && count_snap_back) record_first_reaction();
    if (count_snap_back)
      settled_energy =
          measure_snap_back(pass, settle_start, change, released_before, settled_energy);
    // The last pass's modulus drop is not re-solved: the next step starts from it. Without
    // inertia a pass that only grew damage is re-solved while that growth exceeds
    // fracture.growth_tolerance: a step's end would otherwise carry moduli older than its
    // strain, too stiff by what the step's length alone decided.
    trial_.end_out_of_balance = change.grown > 0;
    const bool settle_growth = count_snap_back && scene_.fracture.growth_tolerance > 0.0 &&
                               change.largest_growth > scene_.fracture.growth_tolerance;
    if (locate_onsets && !settle_growth) {
      const OnsetSearch onset = locate_onset(onset_target(scene_.fracture));
      if (onset.largest > onset_tolerance(scene_.fracture) && onset.fraction && may_cut) {
        trial_.onset_fraction = *onset.fraction;
        trial_.onset_largest = onset.largest;
        return Attempt::cut_at_onset;
      }
      trial_.onset_located = onset.largest >= 1.0;
      break;
    }
    if (change.newly_damaged == 0 && !settle_growth) break;
    // With snap_back = "dynamic" the cascade goes on with inertia from here, in the steps
    // after this one.
    if (change.newly_damaged > 0 && cascade_calls_for_inertia(scene_.fracture, analysis_, pass)) {
      trial_.calls_for_inertia = true;
      break;
    }
    if (pass >= scene_.fracture.max_damage_passes) {
      ++report_.counters.damage_limit_hits;
      break;
    }
    ++report_.counters.damage_iterations;
    prepare_next_pass(inertia.mass_coefficient);
  }
  return increment_acceptable(step, control) ? Attempt::accepted : Attempt::rejected;
}

bool Simulation::follow_turned_frames(long step, int retries, const InertiaTerms& inertia,
                                      StepControl& control) {
  // A solve is linear in the displacement: where it turns a part (one that cracks have nearly
  // cut loose) by theta, it moves the part's nodes along the tangents and stretches its
  // elements by theta^2 / 2 both ways, which the co-rotated strain reads as real (a part of
  // the cushioned disk turned 0.09 rad in one re-solve: 0.43 % of strain, 2.3 J created).
  // Once an element has turned past kFrameTolerance from K's frames (the test a step's start
  // makes), the frames follow and the iterate is corrected by Newton steps from where it is.
  if (!corotational_ || analysis_ == Analysis::dynamic) return true;
  const std::size_t num_dofs = model_.X.size();
  for (int k = 0; k < kMaxFrameCorrections; ++k) {
    for (std::size_t d = 0; d < num_dofs; ++d) trial_.positions[d] = model_.u[d] + trial_.du[d];
    if (!frames_turned_past(model_, trial_.positions, kFrameTolerance)) return true;
    update_element_rotations(model_, trial_.positions);
    system_->invalidate();
    ++report_.counters.frame_corrections;
    {
      ScopedTimer timer(report_.timers.assembly);
      std::copy(trial_.positions.begin(), trial_.positions.end(), trial_.u_trial.begin());
      compute_internal_force(model_, coloring_, trial_.u_trial, model_.strain, model_.stress,
                             trial_.f_int, corotational_, trial_.trial_element_force);
      fragments_.forces(trial_.du, trial_.restraint_force);
    }
    prepare_system(inertia.mass_coefficient);
    if (!open_close_iteration(step, retries, inertia, &control)) return false;
  }
  return true;
}

bool Simulation::carries_load() {
  ScopedTimer timer(report_.timers.detachment);
  const bool joined = joins_moving_and_fixed_boundaries(model_, bc_, committed_.contacts);
  load_path_seen_ = load_path_seen_ || joined;
  return joined || !load_path_seen_;
}

bool Simulation::commit_checked_step(long step, double dt, const EnergyBalance& before,
                                     StepControl& control) {
  // A step of no length (an onset's damage) cannot be redone shorter: it is measured only.
  const bool can_redo = dt > 0.0;
  if (can_redo) {
    rollback_.committed = committed_;
    rollback_.u = model_.u;
    rollback_.v = model_.v;
    rollback_.contacts_committed_before = contact_ && contact_->committed_before();
  }
  commit_step(dt, control);
  const EnergyBalance after = energy();
  const double created = EnergyCheck::created(before, after, trial_.energy.created);
  std::string why;
  if (energy_check_.judge(step, created, after, can_redo, why) != EnergyCheck::Verdict::redo) {
    energy_check_.record(created, after);
    return true;
  }
  // Taken back: the committed state, the motion and the contacts' first commit as they were.
  std::swap(committed_, rollback_.committed);
  std::swap(model_.u, rollback_.u);
  std::swap(model_.v, rollback_.v);
  if (contact_) contact_->set_committed_before(rollback_.contacts_committed_before);
  ++report_.counters.redone_by_energy;
  control.reject(step, why);
  return false;
}

bool Simulation::open_close_iteration(long step, int retries, const InertiaTerms& inertia,
                                      StepControl* control) {
  const std::size_t num_dofs = model_.X.size();
  RunStats& counters = report_.counters;
  // The open-close iteration (a single solve without contacts): assume states, solve, check.
  const int limit = analysis_ == Analysis::dynamic ? kMaxOpenCloseIterations
                                                   : kMaxOpenCloseIterationsWithoutInertia;
  int iterations = 0;
  // The factor already holds this iteration's system: the springs that switched in the last
  // iteration were folded in by updates.
  bool factor_current = false;
  while (true) {
    ++iterations;
    solve_iteration(step, inertia, factor_current);
    if (!contact_) break;
    double penetration = 0.0;
    int changes = 0;
    const std::vector<ContactSprings> before = contact_->springs();
    {
      ScopedTimer timer(report_.timers.contact);
      for (std::size_t d = 0; d < num_dofs; ++d)
        trial_.positions[d] = model_.X[d] + model_.u[d] + trial_.du[d];
      // Contacts that chatter near zero force are indeterminate, not wrong: past half the
      // iteration limit the tolerance doubles each iteration, up to 4x (kMaxRelaxationDoublings),
      // and the summary counts the steps that needed it.
      const int past = std::min(iterations - limit / 2, kMaxRelaxationDoublings);
      const double scale = past > 0 ? std::ldexp(1.0, past) : 1.0;
      // Last resort, in the closing iterations of a step already redone kRetriesBeforeSettling
      // times: contacts that keep swinging between two answers settle on their last one.
      const bool settle =
          retries >= kRetriesBeforeSettling && iterations > limit - kSettlingIterations;
      // The forces this solve's contacts pushed with, before the update switches any: with
      // DDA's inertia they are what the step's kinetic energy went into (commit_step).
      if (analysis_ == Analysis::dynamic && integrator_ == Integrator::dda) {
        std::fill(trial_.contact_force_solved.begin(), trial_.contact_force_solved.end(), 0.0);
        contact_->add_spring_forces(trial_.positions, trial_.contact_force_solved);
      }
      changes = contact_->update_states(trial_.positions, scale, settle, penetration);
      if (changes == 0 && scale > 1.0) {
        ++counters.open_close_relaxed_steps;
        counters.largest_relaxation = std::max(counters.largest_relaxation, scale);
      }
    }
    if (changes == 0) break;
    trial_.contact_changed = true;
    // Factor reuse: the springs that switched are a low-rank change of K. When updating the
    // factor is expected to cost less than refactorizing (docs/benchmarks.md), the
    // next iteration solves with the updated factor; a downdate that fails falls back.
    const ContactStage::SpringChanges& switched = contact_->spring_changes(before, bc_.equation);
    factor_current = system_->update_contact_springs(switched.added, switched.removed);
    if (iterations >= limit) {
      counters.open_close_iterations += iterations;
      if (!control) return false;
      ++counters.redone_by_open_close;
      control->reject(step, "the open-close iteration did not settle in " + std::to_string(limit) +
                                " iterations");
      return false;
    }
  }
  if (contact_) {
    counters.open_close_iterations += iterations;
    counters.max_open_close_per_step = std::max<long>(counters.max_open_close_per_step, iterations);
  }
  return true;
}

void Simulation::solve_iteration(long step, const InertiaTerms& inertia, bool factor_current) {
  const std::size_t num_dofs = model_.X.size();
  if (contact_) {
    {
      ScopedTimer timer(report_.timers.contact);
      std::fill(trial_.f_contact.begin(), trial_.f_contact.end(), 0.0);
      for (std::size_t d = 0; d < num_dofs; ++d)
        trial_.positions[d] = model_.X[d] + trial_.u_trial[d];
      contact_->add_solve_forces(trial_.positions, trial_.f_contact);
      // With Newmark the solve takes the sum of the step's start and end contact forces, of
      // which the committed acceleration already holds the start's.
      if (contact_->energy_consistent())
        for (std::size_t d = 0; d < num_dofs; ++d)
          trial_.f_contact[d] -= committed_.contact_force[d];
    }
    system_->add_contact_springs(contact_->spring_matrices(model_.num_elements()), factor_current);
  }
  for (std::size_t d = 0; d < num_dofs; ++d) {
    const std::int32_t eq = bc_.equation[d];
    if (eq < 0) continue;
    const double m = model_.node_mass[d / 2];
    trial_.rhs[eq] = trial_.f_ext[d] - trial_.f_int[d] - trial_.f_contact[d] -
                     trial_.restraint_force[d] +
                     m * (inertia.velocity_coefficient * model_.v[d] +
                          inertia.acceleration_coefficient * committed_.acceleration[d]);
    // A Newton step from an iterate (follow_turned_frames): the mass term holds what the
    // iterate has already moved.
    if (const double moved = trial_.u_trial[d] - model_.u[d]; moved != 0.0)
      trial_.rhs[eq] -= inertia.mass_coefficient * m * moved;
  }
  system_->solve(trial_.rhs);
  for (std::size_t d = 0; d < num_dofs; ++d) {
    if (bc_.equation[d] >= 0)
      trial_.du[d] = trial_.u_trial[d] - model_.u[d] + trial_.rhs[bc_.equation[d]];
    if (!std::isfinite(trial_.du[d])) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "step %ld: the displacement increment of node %zu is not finite "
                    "(check stiffness contrasts, restraints and dt)",
                    step, d / 2);
      throw RunFailure(buf);
    }
  }
}

bool Simulation::increment_acceptable(long step, StepControl& control) {
  double largest = 0.0;
  for (const double du : trial_.du) largest = std::max(largest, std::abs(du));
  if (!control.displacement_ok(largest)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "largest displacement increment %.3g m exceeds max_step_displacement", largest);
    ++report_.counters.redone_by_displacement;
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
    ++report_.counters.redone_by_displacement;
    control.reject(step, buf);
    return false;
  }
  return true;
}

}  // namespace rockdd

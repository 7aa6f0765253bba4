#pragma once
// The step loop of the paper's flowchart (Fig. 3), and nothing else: each stage lives in its
// own file and this one calls them in order (docs/architecture.md, "The step").
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/assembly/element_coloring.hpp"
#include "engine/common/timers.hpp"
#include "engine/damage/fragment_restraint.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"
#include "engine/report/run_report.hpp"
#include "engine/report/setup_report.hpp"
#include "engine/scene/scene.hpp"
#include "engine/state/committed_state.hpp"
#include "engine/state/step_state.hpp"
#include "engine/time/energy_check.hpp"

namespace rockdd {

class Probes;
class ContactStage;
class DamageStage;
class LinearSystem;
class StepControl;
class OnsetCuts;
struct SolverStats;
struct DamageChange;
struct OnsetSearch;
struct RunResult;  // engine/report/run_result.hpp
struct InertiaTerms;

/// What an observer sees after each committed step.
struct StepReport {
  long step = 0;
  double time = 0, dt = 0, end_time = 0;
  long num_steps = 0;  // planned steps; 0 when time-driven
};

/// What an observer sees as a step attempt starts, from the committed state.
struct AttemptReport {
  long step = 0;
  int retries = 0;  // earlier attempts of this step that were rejected
  double dt = 0;
};

/// How to run: where outputs go, threads, a per-step callback and a caller's stop.
struct RunOptions {
  std::filesystem::path out_root;  // empty: the scene's output.dir
  std::filesystem::path out_dir;   // the run folder itself; empty: <out_root>/<scene name>
  int threads = 0;                 // 0: every hardware thread
  bool write_outputs = true;
  bool write_frames = true;  // VTU frames (history, profiles and summary come regardless)
  std::function<void(const StepReport&, const Model&)> on_step;
  /// Called as each step attempt starts, with the model the attempt starts from: the committed
  /// state, also after a rejected attempt (for diagnosis of redone steps).
  std::function<void(const AttemptReport&, const Model&)> on_attempt;
  /// Asked after each committed step, before its history row: false ends the run there, ok,
  /// with that step's frame written (a caller's own end condition; summary.json then says
  /// "stopped_by_caller": true).
  std::function<bool(const StepReport&, const Model&)> keep_going;
  /// Called as a step commits, for each run event of its damage passes (the first damage, the
  /// first separation into parts), with the model as that pass left it.
  std::function<void(const RunEvent&, const Model&)> on_event;
  /// What came before the Simulation (scene, meshing, model), as its caller measured it; with
  /// it, summary.json's timers account for the whole process.
  std::optional<SetupReport> setup;
};

/// Where a run of `scene` with `options` writes its files.
std::filesystem::path run_folder(const Scene& scene, const RunOptions& options);

/// One simulation of one scene. Construction resolves every name the scene uses and sets
/// up the symbolic stages (pattern, scatter map, colouring, CHOLMOD analysis) once.
class Simulation {
 public:
  /// Throws InputError for a scene the model cannot satisfy (unknown names, unrestrained
  /// static blocks). With `mesh_slot` (BuiltModel::mesh_slot: where the model's mesh is kept
  /// in the mesh cache), the fill-reducing ordering of the first CHOLMOD analysis is taken
  /// from beside the mesh when one was stored for exactly this pattern, and stored there
  /// otherwise: the same ordering, so bitwise the same factor and results, without computing
  /// it again.
  Simulation(Scene scene, Model model, std::optional<MeshCacheSlot> mesh_slot = std::nullopt);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Runs to the end; numerical failures end the run with ok = false and the reason.
  RunResult run(const RunOptions& options);

  const Model& model() const { return model_; }
  const Scene& scene() const { return scene_; }
  /// The solver's counters; complete once run() has returned.
  const SolverStats& solver_stats() const;
  const StageTimers& timers() const { return report_.timers; }

 private:
  /// How a step attempt ended.
  enum class Attempt {
    accepted,
    rejected,      // redo with the step control's smaller dt
    cut_at_onset,  // redo shorter (OnsetCuts): it passed an undamaged element's onset
  };

  // The attempt (simulation.cpp).
  /// One step attempt of length dt from the committed state at `time` (`retries` earlier
  /// attempts of this step were rejected). `cuts`: whether an attempt that passes an onset by
  /// more than its tolerance is cut back, and whether one of no length locates its onsets.
  /// `onset_at_start`: the last step located an onset, whose damage this attempt (of no length)
  /// runs before any solve. A step of no length without either settles the last step's damage
  /// growth and runs the onsets that settling passes.
  Attempt attempt_step(long step, int retries, double time, double dt, double load_factor,
                       StepControl& control, const OnsetCuts& cuts, bool onset_at_start);
  /// The step length whose inertia the system carries: dt, but in a quasi-static analysis,
  /// whose mass term only regularises (the velocity resets each step), the step control's dt
  /// up to the scene's: cutting a step at an onset, or running an onset's damage in a step of
  /// no length, does not stiffen it, while a step redone shorter (its open-close iteration did
  /// not settle) is held back more, as DDA's own step cuts hold loose blocks.
  double inertia_step(double dt, const StepControl& control) const;
  /// The model's working fields, the restraint and the trial state as the attempt starts:
  /// the committed state's, whatever an earlier attempt left.
  void begin_attempt(double time, double load_factor);
  /// Commits an accepted attempt of length dt unless the energy check rejects it: then the
  /// commit is taken back, dt halved (throws RunFailure below dt_min) and false returned.
  /// `before`: the balance of the committed state the attempt started from.
  bool commit_checked_step(long step, double dt, const EnergyBalance& before,
                           StepControl& control);
  /// The open-close iteration of one step from the trial state; false when it did not settle
  /// (and then, given a `control`, the step is rejected there).
  bool open_close_iteration(long step, int retries, const InertiaTerms& inertia,
                            StepControl* control);
  /// After a solve that turned elements past kFrameTolerance from K's frames: the frames
  /// follow and Newton steps correct the iterate from where it is (steps without inertia;
  /// false when such an open-close iteration did not settle).
  bool follow_turned_frames(long step, int retries, const InertiaTerms& inertia,
                            StepControl& control);
  /// One solve of the open-close iteration: contact springs, factorization (unless
  /// `factor_current`), solve; fills the trial's du.
  void solve_iteration(long step, const InertiaTerms& inertia, bool factor_current);
  /// The step's largest displacement increment within the scene's limit and the contact
  /// search distance; otherwise the step is rejected (dt halved) and false returned.
  bool increment_acceptable(long step, StepControl& control);
  /// K + cM and the fragment restraint assembled when the mass coefficient, the moduli, the
  /// frames or the pattern changed; without contacts also factorized.
  void prepare_system(double mass_coefficient);
  /// The system's pattern for the elements and the current contact triples.
  void rebuild_layout();

  // The damage iteration of an attempt (damage_iteration.cpp).
  /// Strain and stress (into the model) and f_int at the step's result u + du.
  void strain_at_result();
  /// Damage laws at the strain and stress strain_at_result() left; moduli marked stale when
  /// damage grew. Without `start_onsets` only elements already damaged change.
  DamageChange evaluate_damage(bool start_onsets);
  /// Where along the attempt, from the committed state to strain_at_result()'s, the first
  /// undamaged element's onset ratio reaches `target` (DamageStage::locate_onset).
  OnsetSearch locate_onset(double target);
  /// Adds to the attempt the run events its last damage pass brought (first damage, first
  /// separation), each with a copy of the model at the pass.
  void note_damage_events();
  /// Fills the trial's reaction_first: the constraints' force at the first solve of the step.
  void record_first_reaction();
  /// Without inertia, after damage pass `pass`: books the energy the rock gave up between the
  /// last pass's modulus drop (stored energy `settled_energy`; the committed state when the
  /// step starts out of balance, `settle_start`) and this solve, less the work done meanwhile,
  /// as snap-back (docs/method-choices.md, "Energy balance"). Returns the stored energy just
  /// after this pass's drop, where the next pass's snap-back starts.
  double measure_snap_back(int pass, bool settle_start, const DamageChange& change,
                           double released_before, double settled_energy);
  /// Energy the rock and its springs hold at the trial increment du (J): elements, contacts
  /// and fragment restraint. Fills the trial's positions with X + u + du.
  double stored_energy();
  /// After a damage pass that newly damaged elements: the restraint of parts it cut loose,
  /// the factor (folded by updates when cheaper, or reassembled) and the trial internal force
  /// under the new moduli.
  void prepare_next_pass(double mass_coefficient);
  /// Without inertia, after a damage pass in which elements broke (w reached 1): a part that
  /// only they joined to what holds it is loose until the step ends and detaches them, so the
  /// fragment restraint is rebuilt over the parts.
  void hold_parts_cut_loose();
  /// Without inertia, after a solve that settles the committed state's imbalance or a damage
  /// pass: when the fragment restraint's springs hold more than fracture.restraint_relaxation
  /// of the stored energy, they are re-anchored where the solve left the parts and the open-close
  /// iteration solves again (on the same factor), until they hold less than kRestraintRelaxed
  /// of that share, so that the parts end where their contacts and the rock balance them, not held
  /// back towards where the step started. A relaxation is taken back exactly (increment,
  /// contacts, anchors) when what the springs hold does not halve (a part only they hold),
  /// when the increment would pass its limits, or when its open-close iteration does not
  /// settle (docs/method-choices.md, "Restraint relaxation").
  void relax_restraint(long step, int retries, const InertiaTerms& inertia,
                       const StepControl& control);

  // The commit and what follows it (commit.cpp).
  /// Velocity, rotations of free blocks, u, stresses, contacts, reactions and work.
  void commit_step(double dt, const StepControl& control);
  /// f_int, strains and stresses at the committed displacement, and each element's force.
  void internal_force_at_commit();
  /// The committed state taken from the model, the trial and the restraint after the step and
  /// its fracture (`detached`: elements detached and everything on the nodes was rebuilt).
  void record_committed_state(bool detached);
  /// After a committed step: damaged elements become blocks, and what hangs on the nodes is
  /// rebuilt for the new topology. True when any element detached.
  bool detach_fractured_elements();
  /// The edge adjacency of model_.conn (edges_): built on first use, then kept through the
  /// detachments' node splits.
  const EdgeAdjacency& current_edges();
  /// Without inertia, after nodes split: the blocks no boundary holds take their current
  /// rotation as their stiffness frame. A stressed piece cut loose with a stale frame meets,
  /// in the linear solve, a moment (its stress times its turn so far) that only the weak
  /// fragment springs resist, and turns by a large angle in one step.
  void turn_loose_block_frames();
  /// After nodes split: loads and constraint forces of the committed state on the new nodes.
  void recompute_committed_forces();
  /// With inertia, Newmark's acceleration that balances the committed state,
  /// a = M^-1 (f_ext - f_int - f_contact) on the free dofs (0 on prescribed ones, and without
  /// inertia).
  void balance_acceleration();
  /// With Newmark and contacts, at the commit: the acceleration the update left balances the
  /// contact forces the solve took (ContactStage::add_solve_forces); it is set to balance the
  /// springs' end forces instead, which committed_.contact_force keeps for the next step.
  void balance_acceleration_at_end_contact_forces();
  /// fracture.snap_back = "dynamic": after the step whose damage cascade called for inertia,
  /// the run goes on as a dynamic analysis (Newmark, snap_back_time_step) from the committed
  /// state, which the last damage pass left out of balance. Throws RunFailure when only
  /// time.end would end the run and it leaves more than 10^6 dynamic steps.
  void follow_cascade_with_inertia(long step, double time, double end_time, StepControl& control);
  /// The energy balance of the committed state, as history.csv and summary.json report it.
  EnergyBalance energy() const;
  /// Whether the committed step joins the moving boundary to a held one through rock and
  /// closed contacts; also true until a step first has (a platen that starts apart).
  bool carries_load();

  Scene scene_;
  Analysis analysis_;      // of the steps: the scene's, until a cascade calls for inertia
  Integrator integrator_;  // of the steps: Newmark once a snap-back is followed with inertia
  Model model_;            // u and v committed; damage, strain and stress the attempt's
  BoundaryConditions bc_;
  std::vector<double> reference_loads_;
  ElementColoring coloring_;
  EdgeAdjacency edges_;                 // of model_.conn, kept through detachments
  std::vector<std::uint8_t> detached_;  // per element
  // A quasi-static specimen that starts in at least one block larger than a fragment ends when
  // fracture leaves none (engine/damage/disintegration).
  bool watch_disintegration_ = false;
  // Such a specimen between a moving and a held boundary also ends once nothing joins them, from
  // the first step that joined them (engine/damage/load_path).
  bool watch_load_path_ = false;
  bool load_path_seen_ = false;
  bool corotational_ = false;  // strain in co-rotated element frames (not in static analysis)
  std::unique_ptr<Probes> probes_;
  std::unique_ptr<ContactStage> contact_;  // only for scenes with [[joint]] or fracture
  std::unique_ptr<DamageStage> damage_;    // only for scenes with damageable materials
  FragmentRestraint fragments_;  // the attempt's: the committed one, and parts it cut loose
  StepState trial_;              // the step being attempted
  CommittedState committed_;     // what every attempt starts from
  RunReport report_;             // counters, timers and monitors, for summary.json
  EnergyCheck energy_check_;     // time.energy_tolerance: what a step may create
  /// What commit_step changes, kept so that a step the energy check rejects is taken back.
  struct Rollback {
    CommittedState committed;
    std::vector<double> u, v;
    bool contacts_committed_before = false;
  } rollback_;
  std::function<void(const AttemptReport&, const Model&)> on_attempt_;  // RunOptions'
  // Declared after the timers it adds to; its destructor waits for a running analysis.
  std::unique_ptr<LinearSystem> system_;
};

}  // namespace rockdd

#pragma once
// The step loop of the paper's flowchart (Fig. 3), and nothing else: each stage lives in
// its own file and this one calls them in order.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/assembly/element_coloring.hpp"
#include "engine/common/timers.hpp"
#include "engine/damage/fragment_restraint.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"
#include "engine/output/run_outputs.hpp"
#include "engine/report/energy_account.hpp"
#include "engine/report/run_stats.hpp"
#include "engine/report/setup_report.hpp"
#include "engine/scene/scene.hpp"
#include "engine/state/step_state.hpp"
#include "engine/time/integrator.hpp"
#include "engine/time/step_control.hpp"

namespace rockdd {

class Probes;
class ContactStage;
class DamageStage;
class LinearSystem;
struct SolverStats;
struct DamageChange;

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
  /// What came before the Simulation (scene, meshing, model), as its caller measured it; with
  /// it, summary.json's timers account for the whole process.
  std::optional<SetupReport> setup;
};

/// Where a run of `scene` with `options` writes its files.
std::filesystem::path run_folder(const Scene& scene, const RunOptions& options);

/// Outcome of a run: "ok", or "failed" with the reason; the summary.json content.
struct RunResult {
  bool ok = true;
  std::string reason;
  nlohmann::json summary;
};

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
  const StageTimers& timers() const { return timers_; }

 private:
  /// One step attempt of length dt from the committed state (`retries` earlier attempts of
  /// this step failed); false when it must be redone.
  bool attempt_step(long step, int retries, double dt, double load_factor, StepControl& control);
  /// K + cM and the fragment restraint assembled when the mass coefficient, the moduli, the
  /// frames or the pattern changed; without contacts also factorized.
  void prepare_system(double mass_coefficient);
  /// The system's pattern for the elements and the current contact triples.
  void rebuild_layout();
  /// Solves one open-close iteration: springs, factorization (unless `factor_current`: the
  /// factor was updated for the springs that switched), solve; fills du_.
  void solve_iteration(long step, const InertiaTerms& inertia, bool factor_current = false);
  void commit_step(double dt);
  /// The open-close iteration of one step from u_trial_; false when it did not settle.
  /// `factor_current`: the factor already holds this step's system (a folded damage pass).
  bool open_close_iteration(long step, int retries, const InertiaTerms& inertia,
                            StepControl& control, bool factor_current = false);
  /// Damage laws at the step's result u + du; moduli marked stale when damage grew.
  DamageChange evaluate_damage();
  /// Without inertia, after a damage pass in which elements broke (w reached 1): a part that
  /// only they joined to what holds it is loose until the step ends and detaches them, so the
  /// fragment restraint is rebuilt over the parts (state_.u_trial's increment sets its force).
  /// True when the springs changed (K must be reassembled).
  bool hold_parts_cut_loose();
  /// After a committed step: damaged elements become blocks, and what hangs on the nodes
  /// is rebuilt for the new topology.
  void detach_fractured_elements();

  /// Elastic energy a damage pass released (J): the damage grown since `damage_before`, at
  /// `strain` (kernels::damage_dissipation).
  double released_by_damage(std::span<const double> damage_before,
                            std::span<const double> strain) const;
  /// Energy the rock and its springs hold at the increment du (J): elements (from model_'s
  /// strain and stress), contacts and fragment restraint. Fills state_.positions with X + u + du.
  double stored_energy();
  /// Without inertia, after damage pass `pass`: books the energy the rock gave up between the
  /// last pass's modulus drop (stored energy `settled_energy`; the committed state when the
  /// step starts out of balance, `settle_start`) and this solve, less the work done meanwhile,
  /// as snap-back (docs/method-choices.md, "Energy balance"). Returns the stored energy just
  /// after this pass's drop, where the next pass's snap-back starts.
  double measure_snap_back(int pass, bool settle_start, const DamageChange& change,
                           double released_before, double settled_energy);
  /// After a damage pass that newly damaged elements: the restraint of parts it cut loose,
  /// the factor (folded by updates when cheaper, or reassembled) and the trial internal force
  /// under the new moduli. True when the factor already holds the next system.
  bool prepare_next_pass(double mass_coefficient, bool grown);
  /// The step's largest displacement increment within the scene's limit and the contact
  /// search distance; otherwise the step is rejected (dt halved) and false returned.
  bool increment_acceptable(long step, StepControl& control);
  /// Fills state_.reaction_first: the constraints' force at the first solve of the step.
  void record_first_reaction();
  /// Without inertia, after nodes split: the blocks no boundary holds take their current
  /// rotation as their stiffness frame. A stressed piece cut loose with a stale frame meets,
  /// in the linear solve, a moment (its stress times its turn so far) that only the weak
  /// fragment springs resist, and turns by a large angle in one step.
  void turn_loose_block_frames();
  /// After nodes split: loads and constraint forces of the committed state on the new nodes.
  void recompute_committed_forces();
  /// With inertia, Newmark's acceleration that balances the committed state,
  /// a = M^-1 (f_ext - f_int - f_contact) on the free dofs (0 on prescribed ones, and without
  /// inertia); from the committed forces in state_.
  void balance_acceleration();
  /// fracture.snap_back = "dynamic": after the step whose damage cascade called for inertia,
  /// the run goes on as a dynamic analysis (Newmark, snap_back_time_step) from the committed
  /// state, which the last damage pass left out of balance. Throws RunFailure when only
  /// time.end would end the run and it leaves more than 10^6 dynamic steps.
  void follow_cascade_with_inertia(long step, double time, double end_time, StepControl& control);
  /// Force scale of the committed state (N): the largest element edge force, load or reaction.
  double element_force_scale() const;
  EnergyBalance energy() const;
  void evaluate_probes(std::vector<double>& row);
  nlohmann::json summary(const RunResult& result, double wall_seconds, int threads,
                         const std::optional<SetupReport>& setup) const;
  /// summary.json's "timers": the step stages, the set-up, and with `setup` the whole process.
  nlohmann::json timers_summary(double wall_seconds, const std::optional<SetupReport>& setup) const;

  Scene scene_;
  Analysis analysis_;      // of the steps: the scene's, until a cascade calls for inertia
  Integrator integrator_;  // of the steps: Newmark once a snap-back is followed with inertia
  Model model_;
  BoundaryConditions bc_;
  std::vector<double> reference_loads_;
  ElementColoring coloring_;
  bool corotational_ = false;  // strain in co-rotated element frames (not in static analysis)
  std::function<void(const AttemptReport&, const Model&)> on_attempt_;  // RunOptions'
  std::unique_ptr<Probes> probes_;
  std::unique_ptr<ContactStage> contact_;  // only for scenes with [[joint]]
  std::unique_ptr<DamageStage> damage_;    // only for scenes with damageable materials
  std::vector<std::uint8_t> detached_;     // per element
  std::vector<double> committed_strain_, committed_stress_;
  std::vector<double> committed_damage_;  // w at the last committed step: a redone attempt
                                          // starts from it, not from its failed attempt's
  /// Where damage first appeared: the elements of the first damage pass that found any.
  struct FirstDamage {
    long step = 0;
    double time = 0.0;
    std::int32_t elements = 0;
    double x = 0.0, y = 0.0;  // mean reference centroid of those elements
    double spread = 0.0;      // largest distance of their centroids from that mean
  };
  std::optional<FirstDamage> first_damage_, attempt_first_damage_;
  double attempt_time_ = 0.0;        // time at the end of the step being attempted
  FragmentRestraint fragments_;      // loose blocks held in steps without inertia
  bool loose_parts_held_ = false;    // fragments_ holds parts the attempt's cascade cut loose
  bool inertia_called_for_ = false;  // the attempt's cascade calls for inertia (snap_back)
  /// Where a quasi-static run went on with inertia (fracture.snap_back = "dynamic").
  struct InertiaSwitch {
    long step = 0;  // the last quasi-static step
    double time = 0.0;
    double dt = 0.0;  // of the dynamic steps after it
  };
  std::optional<InertiaSwitch> inertia_switch_;
  EdgeAdjacency edges_;  // of model_.conn, kept through detachments

  EnergyAccount energy_;               // work and losses beside the state's own energy
  std::vector<double> damage_before_;  // per element, before a damage pass

  /// The peak of the watched history column and whether it has softened past the scene's
  /// fraction (time.stop_at_softening).
  struct Softening {
    double peak = 0.0, peak_time = 0.0;
    long peak_step = 0;
    bool reached = false;
    long step = 0;
    double time = 0.0, value = 0.0;
    /// True once |value| has fallen `drop` below the largest magnitude seen before.
    bool observe(long at_step, double at_time, double v, double drop);
    nlohmann::json summary(const TimeSpec& time) const;
  };
  Softening softening_;
  StepState state_;  // the step's arrays
  RunStats stats_;   // what the run did, for summary.json
  StageTimers timers_;
  SetupTimers setup_timers_;
  // Declared after the timers it adds to; its destructor waits for a running analysis.
  std::unique_ptr<LinearSystem> system_;
};

}  // namespace rockdd

#pragma once
// The global system of a step, K_eff du = r, and everything that changes it: the stiffness
// pattern (analysed again only when contacts or blocks change it), the assembled values, the
// factor and its low-rank updates. The one place where the global matrix or its factor
// changes: the stages hand it element matrices, springs and damage changes.
#include <oneapi/tbb/task_group.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/low_rank_terms.hpp"
#include "engine/assembly/slot_matrices.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/common/timers.hpp"
#include "engine/mesh/mesh_cache.hpp"
#include "engine/model/model.hpp"
#include "engine/solver/cholmod_solver.hpp"

namespace rockdd {

/// Counters of the system's updated factors, for summary.json.
struct LinearSystemStats {
  long folded_damage_passes = 0;      // damage changes folded into the factor by updates
  long untrusted_updated_solves = 0;  // solves with an updated factor that failed the check
};

/// The restraint springs that join K's diagonal: dof and stiffness (N/m) of each.
struct DiagonalSprings {
  std::span<const std::int32_t> dofs;
  std::span<const double> stiffness;
};

/// What the fill-reducing ordering may use besides the pattern.
struct OrderingHints {
  std::span<const double> node_xy;                   // x and y of each node; empty: unknown
  OrderingEffort effort = OrderingEffort::thorough;  // quick when factorized once
};

/// Pattern, values and factor of K_eff = K + c M (+ restraint springs, + contact springs).
class LinearSystem {
 public:
  /// `timers`: the run's stage timers, which the layout, analysis, assembly, factorizations
  /// and solves add to. With `mesh_slot` (where the model's mesh lies in the mesh cache), the
  /// first analysis takes its fill-reducing ordering from beside the mesh when one was stored
  /// for exactly this pattern, and stores it there otherwise: bitwise the same factor.
  /// `factor_updates` (solver.factor_updates): low-rank updates allowed when cheaper.
  LinearSystem(StageTimers& timers, std::optional<MeshCacheSlot> mesh_slot, bool factor_updates);
  /// Waits for a running analysis (it reads this object).
  ~LinearSystem();
  LinearSystem(const LinearSystem&) = delete;
  LinearSystem& operator=(const LinearSystem&) = delete;

  /// A new pattern for the elements and contact triples `conn` (3 nodes each) over the
  /// equations `equation` (per dof, -1 when prescribed). CHOLMOD's analysis runs beside the
  /// scatter map; the solver waits for it before it factorizes. With `contact_springs`, the
  /// springs of each open-close iteration join the assembled values at every factorization.
  /// `ordering`: what the fill-reducing ordering may use besides the pattern.
  void rebuild(std::span<const std::int32_t> conn, std::int32_t num_nodes,
               std::span<const std::int32_t> equation, std::int32_t num_equations,
               bool contact_springs, const OrderingHints& ordering = {});
  /// Waits for the analysis rebuild() started, and rethrows what it threw.
  void await_analysis();

  /// The element frames, the restraint or the mass term changed: the next prepare()
  /// assembles. (A change of damage alone needs no call: prepare() finds it.)
  void invalidate() {
    assembled_for_.reset();
    factor_holds_base_ = false;
    factored_springs_.reset();
  }
  /// Makes the values K + c M (c = `mass_coefficient`) + the restraint's springs at the
  /// model's damage, and without contact springs factorizes them. Values assembled for this c
  /// follow a change of damage since (a damage pass, or an attempt taken back) by the rank-3
  /// terms of the changed elements, folded into the factor by updates when cheaper; otherwise
  /// they are assembled afresh and the factor waits for the next factorization. So a step
  /// starts from the factor of the last solve, carried across steps while the solve check
  /// (solve()) trusts it.
  void prepare(const Model& model, const ElementColoring& coloring,
               std::span<const std::int32_t> equation, double mass_coefficient,
               DiagonalSprings restraint);
  /// K_eff plus the contact springs `springs`; factorized unless `factor_current` (the factor
  /// already holds exactly this system: updated for the springs that switched), or unless the
  /// factor is already that of these very springs on the current base values (an attempt
  /// redone or cut back with nothing changed, or a damage change folded in).
  void add_contact_springs(const SlotMatrices& springs, bool factor_current);
  /// The springs that switched in an open-close iteration, folded into the factor when an
  /// update is expected to cost less than a factorization. True when the factor now holds
  /// the next iteration's system; false leaves the factorization to add_contact_springs.
  bool update_contact_springs(const LowRankTerms& added, const LowRankTerms& removed);
  /// x = K_eff^{-1} x. While the factor carries updates, the answer is checked against the
  /// assembled values by its backward error and the matrix refactorized if the check fails.
  void solve(std::span<double> x);
  /// The largest backward error a solve with an updated factor may have (1e-10; tests set 0
  /// to force the refactorization).
  void set_trusted_backward_error(double largest) { trusted_backward_error_ = largest; }

  const StiffnessLayout& layout() const { return layout_; }
  std::int32_t num_equations() const { return num_equations_; }
  const SolverStats& solver_stats() const { return solver_.stats(); }
  const LinearSystemStats& stats() const { return stats_; }
  /// Whether the first analysis took its ordering from the mesh cache.
  MeshCacheOutcome ordering_cache() const { return ordering_cache_; }

 private:
  /// CHOLMOD's analysis of layout_.pattern; the first one through the ordering cache.
  void analyze();
  /// The values the assembly, restraint and damage changes write: without contact springs
  /// the factorized values themselves, with them the base the springs join.
  std::span<double> base() { return contact_springs_ ? base_values_ : values_; }
  void factorize();
  /// Folds the damage change since values_damage_ (elements `changed_`) into the factor and
  /// the values; false when an update is not expected to pay or failed (the factor is then
  /// stale, the values untouched).
  bool fold_damage_change(const Model& model, std::span<const std::int32_t> equation);

  StageTimers& timers_;
  bool factor_updates_;
  StiffnessLayout layout_;
  std::vector<double> equation_xy_;  // x and y of each equation's node, for the ordering
  OrderingEffort ordering_effort_ = OrderingEffort::thorough;
  std::int32_t num_equations_ = 0;
  CholmodSolver solver_;
  std::optional<MeshCacheSlot> mesh_slot_;  // until the first analysis has used it
  MeshCacheOutcome ordering_cache_ = MeshCacheOutcome::off;
  bool contact_springs_ = false;
  std::vector<double> values_;           // K_eff as factorized, pattern order
  std::vector<double> base_values_;      // K + c M + restraint, without contact springs
  std::optional<double> assembled_for_;  // the mass coefficient the values hold; none: stale
  std::vector<double> values_damage_;    // the element damage the values hold
  std::vector<std::int32_t> changed_;    // elements whose damage differs from values_damage_
  // The factor is that of the base values (without contact springs: of values_)...
  bool factor_holds_base_ = false;
  // ... plus these contact springs, when they are known.
  std::optional<SlotMatrices> factored_springs_;
  LowRankTerms moduli_added_, moduli_removed_;
  std::vector<double> check_rhs_, check_residual_;  // the updated-factor check's work arrays
  LinearSystemStats stats_;
  // docs/benchmarks.md, "Damage passes folded into the factor", for the threshold's table.
  double trusted_backward_error_ = 1e-10;
  bool analysis_pending_ = false;  // analysis_task_ holds a task no one waited for
  // Declared last, so destroyed first: a task still running reads the members above.
  tbb::task_group analysis_task_;
};

}  // namespace rockdd

#include "engine/solver/linear_system.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/modulus_change.hpp"
#include "engine/common/errors.hpp"

namespace rockdd {

LinearSystem::LinearSystem(StageTimers& timers, std::optional<MeshCacheSlot> mesh_slot,
                           bool factor_updates)
    : timers_(timers), factor_updates_(factor_updates), mesh_slot_(std::move(mesh_slot)) {}

LinearSystem::~LinearSystem() {
  try {
    await_analysis();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a failed analysis no one will use
  }
}

void LinearSystem::rebuild(std::span<const std::int32_t> conn, std::int32_t num_nodes,
                           std::span<const std::int32_t> equation, std::int32_t num_equations,
                           bool contact_springs, const OrderingHints& ordering) {
  await_analysis();  // the solver's last analysis is replaced
  ScopedTimer timer(timers_.layout);
  num_equations_ = num_equations;
  ordering_effort_ = ordering.effort;
  equation_xy_.clear();
  if (ordering.node_xy.size() == 2 * static_cast<std::size_t>(num_nodes))
    equation_xy_ = equation_positions(ordering.node_xy, equation, num_equations);
  contact_springs_ = contact_springs;
  layout_ = build_sparsity_pattern(conn, num_nodes, equation);
  // CHOLMOD's analysis needs the pattern alone: it runs beside the scatter map and the
  // assembly (the same analysis whatever runs beside it).
  if (num_equations > 0) {
    analysis_pending_ = true;
    analysis_task_.run([this] {
      analyze();
      mesh_slot_.reset();  // later layouts follow the contacts: computed each time, not stored
    });
  } else {
    mesh_slot_.reset();
  }
  build_scatter_map(conn, equation, layout_);
  values_.assign(static_cast<std::size_t>(layout_.pattern.nnz()), 0.0);
  if (contact_springs_) base_values_.assign(values_.size(), 0.0);
  invalidate();  // the values must be assembled into the new pattern
}

void LinearSystem::await_analysis() {
  if (!analysis_pending_) return;
  ScopedTimer timer(timers_.analysis);
  analysis_pending_ = false;
  analysis_task_.wait();  // rethrows what the analysis threw
}

void LinearSystem::analyze() {
  const SparsityPattern& pattern = layout_.pattern;
  if (!mesh_slot_) {
    solver_.analyze(pattern, equation_xy_, ordering_effort_);
    return;
  }
  // The stored entry holds the pattern it was computed for: another restraint, contact or
  // model of the same mesh is a miss, never another pattern's ordering.
  // The effort chooses among the orderings too: a scene factorized once stores another.
  const std::string key = solver_.ordering_key() + " effort " +
                          (ordering_effort_ == OrderingEffort::quick ? "quick" : "thorough");
  if (std::optional<CachedOrdering> stored =
          read_cached_ordering(*mesh_slot_, key, pattern.col_ptr, pattern.row_idx)) {
    if (const std::optional<FillOrdering> method = fill_ordering_from_name(stored->method)) {
      solver_.analyze_given(pattern, stored->perm, *method);
      ordering_cache_ = MeshCacheOutcome::hit;
      return;
    }
  }
  solver_.analyze(pattern, equation_xy_, ordering_effort_);
  write_cached_ordering(
      *mesh_slot_, key, pattern.col_ptr, pattern.row_idx,
      {solver_.permutation(), std::string(fill_ordering_name(solver_.stats().ordering))});
  ordering_cache_ = MeshCacheOutcome::miss;
}

void LinearSystem::factorize() {
  await_analysis();
  ScopedTimer timer(timers_.factorization);
  solver_.factorize(values_.data());
}

void LinearSystem::prepare(const Model& model, const ElementColoring& coloring,
                           std::span<const std::int32_t> equation, double mass_coefficient,
                           DiagonalSprings restraint) {
  if (num_equations_ == 0) return;
  if (assembled_for_ == mass_coefficient) {
    changed_elements(model, values_damage_, changed_);
    if (!changed_.empty() && !fold_damage_change(model, equation)) assembled_for_.reset();
  }
  if (assembled_for_ != mass_coefficient) {
    ScopedTimer timer(timers_.assembly);
    const std::span<double> target = base();
    assemble_stiffness(model, coloring, layout_, equation, mass_coefficient, target);
    for (std::size_t i = 0; i < restraint.dofs.size(); ++i) {
      const std::int32_t eq = equation[restraint.dofs[i]];
      if (eq >= 0) target[layout_.diagonal[eq]] += restraint.stiffness[i];
    }
    assembled_for_ = mass_coefficient;
    values_damage_ = model.damage;
    factor_holds_base_ = false;
    factored_springs_.reset();
  }
  if (!contact_springs_ && !factor_holds_base_) {  // else with the springs, when they are known
    factorize();
    factor_holds_base_ = true;
  }
}

bool LinearSystem::fold_damage_change(const Model& model, std::span<const std::int32_t> equation) {
  // Only a factor of exactly these values can follow them; and a fresh assembly is the
  // better start for a factorization that is due anyway.
  const bool factor_known = factor_holds_base_ && (!contact_springs_ || factored_springs_);
  if (!factor_updates_ || !factor_known) return false;
  await_analysis();
  ScopedTimer timer(timers_.factorization);
  modulus_change_terms(model, equation, changed_, values_damage_, moduli_added_, moduli_removed_);
  const std::int64_t columns = moduli_added_.num_columns() + moduli_removed_.num_columns();
  if (!solver_.update_expected_faster(columns)) return false;
  try {
    if (moduli_removed_.num_columns() > 0) solver_.update(moduli_removed_, false);
    if (moduli_added_.num_columns() > 0) solver_.update(moduli_added_, true);
  } catch (const RunFailure&) {
    factor_holds_base_ = false;  // unusable: refactorized from fresh values
    factored_springs_.reset();
    return false;
  }
  add_modulus_change(model, layout_, changed_, values_damage_, base());
  if (contact_springs_) add_modulus_change(model, layout_, changed_, values_damage_, values_);
  for (const std::int32_t e : changed_) values_damage_[e] = model.damage[e];
  ++stats_.folded_damage_passes;
  return true;
}

void LinearSystem::add_contact_springs(const SlotMatrices& springs, bool factor_current) {
  if (!factor_current && factor_holds_base_ && factored_springs_ &&
      factored_springs_->slot == springs.slot && factored_springs_->upper == springs.upper)
    return;  // values_ and the factor are already these
  factored_springs_.reset();
  std::copy(base_values_.begin(), base_values_.end(), values_.begin());
  for (std::size_t i = 0; i < springs.size(); ++i)
    scatter_element_matrix(layout_, springs.slot[i],
                           &springs.upper[i * static_cast<std::size_t>(kElementUpperEntries)],
                           values_);
  if (num_equations_ == 0) return;
  if (!factor_current) factorize();
  factor_holds_base_ = true;
  factored_springs_ = springs;
}

bool LinearSystem::update_contact_springs(const LowRankTerms& added, const LowRankTerms& removed) {
  if (num_equations_ == 0) return false;
  ScopedTimer timer(timers_.factorization);
  const std::int64_t columns = added.num_columns() + removed.num_columns();
  if (!factor_updates_ || !solver_.update_expected_faster(columns)) return false;
  // The factor leaves the springs it was known for: add_contact_springs names the new ones.
  factored_springs_.reset();
  try {
    if (added.num_columns() > 0) solver_.update(added, true);
    if (removed.num_columns() > 0) solver_.update(removed, false);
    return true;
  } catch (const RunFailure&) {
    factor_holds_base_ = false;
    return false;  // refactorized from the springs in the next iteration
  }
}

void LinearSystem::solve(std::span<double> rhs) {
  if (num_equations_ == 0) return;
  ScopedTimer timer(timers_.solve);
  double* x = rhs.data();
  if (solver_.supernodal()) {  // a fresh factorization: as accurate as CHOLMOD makes it
    solver_.solve(x, x);
    return;
  }
  // The factor carries low-rank updates, whose round-off grows with each downdate: the
  // solution is checked against the assembled matrix by its normwise backward error
  // |b - A x| / (max|A| |x| + |b|), max norm (an SPD matrix's largest entry is on its
  // diagonal), and the matrix refactorized when that exceeds trusted_backward_error_ (1e-10).
  // Iterative refinement with the updated factor was tried and dropped: on the UCS, the disk and
  // the sliding block every solve was either already below 64 eps or did not improve in 30
  // refinements (docs/benchmarks.md, "Damage passes folded into the factor", for the threshold's
  // table).
  const auto n = static_cast<std::size_t>(num_equations_);
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
  if (!(scale > 0.0) || residual <= trusted_backward_error_ * scale) return;
  ++stats_.untrusted_updated_solves;
  {
    ScopedTimer refactorization(timers_.factorization);
    solver_.factorize(values_.data());
  }
  std::copy(check_rhs_.begin(), check_rhs_.end(), x);
  solver_.solve(x, x);
}

}  // namespace rockdd

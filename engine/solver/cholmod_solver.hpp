#pragma once
// CHOLMOD supernodal Cholesky with its symbolic and numeric phases kept apart:
// analyze once per sparsity pattern, factorize whenever the values change, solve often,
// and modify the factor by a low-rank term (A +/- C C^T) when only a few springs change.
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/assembly/low_rank_terms.hpp"
#include "engine/assembly/sparsity_pattern.hpp"
#include "engine/solver/fill_reducing_ordering.hpp"

namespace rockdd {

/// Counters that summary.json reports under "solver".
struct SolverStats {
  std::int64_t analyses = 0;
  std::int64_t factorizations = 0;
  std::int64_t updates = 0;                 // update() calls that changed the factor
  std::int64_t updated_columns = 0;         // their total rank (columns of C)
  std::int64_t simplicial_conversions = 0;  // supernodal factors turned simplicial for updates
  double last_factor_flops = 0.0;           // cholmod_common.fl of the last factorization
  double last_factor_seconds = 0.0;
  double factor_nonzeros = 0.0;        // nnz(L) of the last analysis (cholmod_common.lnz)
  double analysis_flops = 0.0;         // the flops it predicts per factorization
  double last_analysis_seconds = 0.0;  // the last analyze(), ordering included
  double analysis_seconds = 0.0;       // every analyze(), on whichever thread ran it
  FillOrdering ordering = FillOrdering::cholmod;  // the ordering the last analysis kept
  double last_update_seconds = 0.0;               // the last update(), its conversion included
};

/// Owns the CHOLMOD state (common, symbolic factor, numeric factor) of one SPD system.
class CholmodSolver {
 public:
  explicit CholmodSolver(FillOrdering ordering = FillOrdering::node);
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Symbolic analysis (fill-reducing ordering, supernodes) with the constructor's ordering.
  /// A node-graph ordering is given to CHOLMOD, which then tries no other. The analysis keeps
  /// the lower triangle of the permuted pattern, P A P^T, that factorize() hands to CHOLMOD.
  /// `equation_xy` (x and y of each equation's node; empty when unknown) lets the node
  /// strategy dissect by coordinates; with OrderingEffort::quick METIS is then not tried.
  void analyze(const SparsityPattern& pattern, std::span<const double> equation_xy = {},
               OrderingEffort effort = OrderingEffort::thorough);
  /// Symbolic analysis with a known elimination order: `perm` is permutation() of an earlier
  /// analysis of the same pattern (perm[k]: the equation eliminated k-th). CHOLMOD takes it as
  /// it is (no postordering, no other method), so the analysis, and every factor of it, is
  /// bitwise that earlier analysis's; `kept` is the ordering stats() then reports. Throws
  /// std::invalid_argument when perm is not a permutation of the pattern's equations.
  void analyze_given(const SparsityPattern& pattern, std::span<const std::int32_t> perm,
                     FillOrdering kept);
  /// The elimination order of the last analysis: perm[k] is the equation of the factor's
  /// column k. Empty before an analysis.
  const std::vector<std::int32_t>& permutation() const;
  /// What the orderings of this solver depend on besides the pattern, as text: the strategy
  /// of the constructor, the versions of CHOLMOD, AMD and METIS, and a hash of the solver's
  /// code. Part of the key of a stored ordering.
  std::string ordering_key() const;
  /// Numeric factorization of the analysed pattern with these values (pattern order), always
  /// supernodal LL^T, whatever updates the previous factor went through.
  /// Throws RunFailure naming the column when the matrix is not positive definite.
  void factorize(const double* values);
  /// The factor of A + C C^T (add) or A - C C^T (!add), where A is the matrix the factor
  /// currently represents; equals factorize() of the modified values up to rounding. The first
  /// update after a factorization turns the factor into simplicial LDL^T (cholmod_updown works
  /// on that form only; the conversion costs 0.1-0.2 factorizations), later ones modify it in
  /// place. Each column costs about the work along its elimination-tree path to the root: on
  /// 2D meshes one factorization buys 85 columns at 1e4 dofs, 150 at 1e5, 450 at 1e6.
  /// Throws RunFailure when a downdate leaves the matrix not positive definite; the factor is
  /// then unusable until the next factorize().
  void update(const LowRankTerms& terms, bool add);
  /// Whether update() with `columns` columns is expected to cost less than factorize(), by a
  /// fixed cost model (0.45 sqrt(n) + 4000 / sqrt(max(n, 5e3)) columns per factorization,
  /// plus 0.15 factorizations for the conversion while the factor is supernodal), never by
  /// timings: the choice changes round-off, and results must not depend on the machine's load.
  /// False without a factorization.
  bool update_expected_faster(std::int64_t columns) const;
  /// x = A^{-1} b for the current factor (factorized, then updated); b and x have n entries
  /// per column (`columns` of them, one after the other) and may alias. Several columns share
  /// one pass over the factor (BLAS-3 in the supernodes).
  void solve(const double* b, double* x, int columns = 1);

  bool analyzed() const;
  /// Whether the factor is supernodal (false once update() has turned it simplicial).
  bool supernodal() const;
  const SolverStats& stats() const { return stats_; }

 private:
  /// After CHOLMOD's analysis: the ordering taken out of the factor and tril(P A P^T) (unless
  /// `permuted_already`: analyze_given() built them before), stats.
  void finish_analysis(const SparsityPattern& pattern, FillOrdering kept,
                       std::chrono::steady_clock::time_point start, bool permuted_already = false);

  struct State;
  std::unique_ptr<State> state_;
  SolverStats stats_;
  FillOrdering ordering_;
};

}  // namespace rockdd

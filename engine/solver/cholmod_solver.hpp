#pragma once
// CHOLMOD supernodal Cholesky with its symbolic and numeric phases kept apart:
// analyze once per sparsity pattern, factorize whenever the values change, solve often.
#include <cstdint>
#include <memory>

#include "engine/assembly/sparsity_pattern.hpp"

namespace rockdd {

/// Counters that summary.json reports under "solver".
struct SolverStats {
  std::int64_t analyses = 0;
  std::int64_t factorizations = 0;
  std::int64_t updates = 0;
  double last_factor_flops = 0.0;  // cholmod_common.fl of the last factorization
  double last_factor_seconds = 0.0;
};

/// Owns the CHOLMOD state (common, symbolic factor, numeric factor) of one SPD system.
class CholmodSolver {
 public:
  CholmodSolver();
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Symbolic analysis (fill-reducing ordering, supernodes). Copies the pattern.
  void analyze(const SparsityPattern& pattern);
  /// Numeric factorization of the analysed pattern with these values (pattern order).
  /// Throws RunFailure naming the column when the matrix is not positive definite.
  void factorize(const double* values);
  /// x = A^{-1} b for the last factorization; b and x have n entries and may alias.
  void solve(const double* b, double* x);

  bool analyzed() const;
  const SolverStats& stats() const { return stats_; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  SolverStats stats_;
};

}  // namespace rockdd

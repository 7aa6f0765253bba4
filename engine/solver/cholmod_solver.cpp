#include "engine/solver/cholmod_solver.hpp"

#include <cholmod.h>
#include <omp.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "engine/errors.hpp"

namespace rockdd {
namespace {

/// Debian's CHOLMOD opens an OpenMP parallel region (num_threads clause, so
/// omp_set_num_threads cannot stop it) around small loops of every supernode; on 2D meshes
/// waking a team per supernode costs more than the loops. With max-active-levels at 0 every
/// region runs inactive on the calling thread. The caller's setting is restored afterwards.
class SerialOpenMpRegions {
 public:
  SerialOpenMpRegions() : saved_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMpRegions() { omp_set_max_active_levels(saved_); }
  SerialOpenMpRegions(const SerialOpenMpRegions&) = delete;
  SerialOpenMpRegions& operator=(const SerialOpenMpRegions&) = delete;

 private:
  int saved_;
};

}  // namespace

struct CholmodSolver::State {
  cholmod_common common{};
  SparsityPattern pattern;
  cholmod_sparse matrix{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* x = nullptr;
  cholmod_dense* y_work = nullptr;
  cholmod_dense* e_work = nullptr;
  cholmod_dense rhs{};

  State() {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_ll = true;
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~State() {
    cholmod_free_dense(&x, &common);
    cholmod_free_dense(&y_work, &common);
    cholmod_free_dense(&e_work, &common);
    cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }

  /// A header over our own arrays: CHOLMOD reads the pattern and values in place.
  void point_matrix_at(double* values) {
    matrix.nrow = matrix.ncol = static_cast<std::size_t>(pattern.n);
    matrix.nzmax = static_cast<std::size_t>(pattern.nnz());
    matrix.p = pattern.col_ptr.data();
    matrix.i = pattern.row_idx.data();
    matrix.nz = nullptr;
    matrix.x = values;
    matrix.z = nullptr;
    matrix.stype = 1;  // upper triangle of a symmetric matrix
    matrix.itype = CHOLMOD_INT;
    matrix.xtype = values ? CHOLMOD_REAL : CHOLMOD_PATTERN;
    matrix.dtype = CHOLMOD_DOUBLE;
    matrix.sorted = 1;
    matrix.packed = 1;
  }
};

CholmodSolver::CholmodSolver() : state_(std::make_unique<State>()) {}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::analyzed() const { return state_->factor != nullptr; }

void CholmodSolver::analyze(const SparsityPattern& pattern) {
  State& s = *state_;
  SerialOpenMpRegions serial;
  cholmod_free_factor(&s.factor, &s.common);
  s.pattern = pattern;
  s.point_matrix_at(nullptr);
  s.factor = cholmod_analyze(&s.matrix, &s.common);
  if (s.factor == nullptr || s.common.status < CHOLMOD_OK)
    throw std::runtime_error("CHOLMOD analysis failed (status " + std::to_string(s.common.status) + ")");
  ++stats_.analyses;
}

void CholmodSolver::factorize(const double* values) {
  State& s = *state_;
  if (s.factor == nullptr) throw std::logic_error("CholmodSolver::factorize before analyze");
  SerialOpenMpRegions serial;
  s.point_matrix_at(const_cast<double*>(values));  // CHOLMOD only reads A
  const auto start = std::chrono::steady_clock::now();
  cholmod_factorize(&s.matrix, s.factor, &s.common);
  stats_.last_factor_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats_.last_factor_flops = s.common.fl;
  ++stats_.factorizations;
  if (s.common.status == CHOLMOD_NOT_POSDEF) {
    throw RunFailure("the system matrix is not positive definite (CHOLMOD stopped at column " +
                     std::to_string(s.factor->minor) + " of " + std::to_string(s.pattern.n) +
                     "): a body is unrestrained or an element has lost its stiffness");
  }
  if (s.common.status < CHOLMOD_OK)
    throw RunFailure("CHOLMOD factorization failed (status " + std::to_string(s.common.status) + ")");
}

void CholmodSolver::solve(const double* b, double* x) {
  State& s = *state_;
  SerialOpenMpRegions serial;
  const auto n = static_cast<std::size_t>(s.pattern.n);
  s.rhs.nrow = n;
  s.rhs.ncol = 1;
  s.rhs.nzmax = n;
  s.rhs.d = n;
  s.rhs.x = const_cast<double*>(b);  // read only
  s.rhs.z = nullptr;
  s.rhs.xtype = CHOLMOD_REAL;
  s.rhs.dtype = CHOLMOD_DOUBLE;
  // cholmod_solve2 reuses x and the workspaces across calls: no allocation per solve.
  cholmod_solve2(CHOLMOD_A, s.factor, &s.rhs, nullptr, &s.x, nullptr, &s.y_work, &s.e_work, &s.common);
  if (s.x == nullptr || s.common.status < CHOLMOD_OK) throw RunFailure("CHOLMOD solve failed");
  const auto* solution = static_cast<const double*>(s.x->x);
  std::copy(solution, solution + n, x);
}

}  // namespace rockdd

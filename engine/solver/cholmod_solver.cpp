#include "engine/solver/cholmod_solver.hpp"

#include <cholmod.h>
#include <malloc.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "engine/errors.hpp"
#include "engine/solver/serial_openmp_regions.hpp"

extern "C" {
// OpenBLAS's own thread control (declared in its cblas.h, whose path depends on the variant).
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);
}

namespace rockdd {
namespace {

/// Below this many flops a factorization runs its BLAS on one thread: a second OpenBLAS
/// thread spins (sched_yield) more than it helps. Measured on 2D CST meshes: 1 thread is
/// faster at 2.1e9 flops (96 ms against 106 ms), 2 threads at 5.3e10 (1.85 s against 1.98 s).
constexpr double kParallelBlasFlops = 1e10;

/// Sets OpenBLAS's thread count for one scope and restores it.
class BlasThreads {
 public:
  explicit BlasThreads(int threads) : saved_(openblas_get_num_threads()) {
    if (threads != saved_) openblas_set_num_threads(threads);
  }
  ~BlasThreads() {
    if (openblas_get_num_threads() != saved_) openblas_set_num_threads(saved_);
  }
  BlasThreads(const BlasThreads&) = delete;
  BlasThreads& operator=(const BlasThreads&) = delete;

 private:
  int saved_;
};

/// CHOLMOD allocates its supernodal workspace on every factorization. glibc serves blocks
/// above 128 KiB with mmap and returns them at free, so each factorization page-faults its
/// workspace in again (at 1e6 dofs: 1.85 s instead of 1.69 s). Keeping large blocks in the
/// heap lets the next factorization reuse the same memory. Done once per process.
void keep_large_blocks_in_heap() {
  static const bool done = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    return true;
  }();
  (void)done;
}

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
  int blas_threads = 1;

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

CholmodSolver::CholmodSolver() : state_(std::make_unique<State>()) {
  keep_large_blocks_in_heap();
}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::analyzed() const {
  return state_->factor != nullptr;
}

void CholmodSolver::analyze(const SparsityPattern& pattern) {
  State& s = *state_;
  SerialOpenMpRegions serial;
  cholmod_free_factor(&s.factor, &s.common);
  s.pattern = pattern;
  s.point_matrix_at(nullptr);
  s.factor = cholmod_analyze(&s.matrix, &s.common);
  if (s.factor == nullptr || s.common.status < CHOLMOD_OK)
    throw std::runtime_error("CHOLMOD analysis failed (status " + std::to_string(s.common.status) +
                             ")");
  // The analysis leaves the factorization's flop count in Common->fl.
  s.blas_threads = s.common.fl > kParallelBlasFlops ? openblas_get_num_threads() : 1;
  ++stats_.analyses;
}

void CholmodSolver::factorize(const double* values) {
  State& s = *state_;
  if (s.factor == nullptr) throw std::logic_error("CholmodSolver::factorize before analyze");
  SerialOpenMpRegions serial;
  BlasThreads blas(s.blas_threads);
  s.point_matrix_at(const_cast<double*>(values));  // CHOLMOD only reads A
  const auto start = std::chrono::steady_clock::now();
  cholmod_factorize(&s.matrix, s.factor, &s.common);
  stats_.last_factor_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats_.last_factor_flops = s.common.fl;
  ++stats_.factorizations;
  if (s.common.status == CHOLMOD_NOT_POSDEF) {
    throw RunFailure("the system matrix is not positive definite (CHOLMOD stopped at column " +
                     std::to_string(s.factor->minor) + " of " + std::to_string(s.pattern.n) +
                     "): a body is unrestrained or an element has lost its stiffness");
  }
  if (s.common.status < CHOLMOD_OK)
    throw RunFailure("CHOLMOD factorization failed (status " + std::to_string(s.common.status) +
                     ")");
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
  cholmod_solve2(CHOLMOD_A, s.factor, &s.rhs, nullptr, &s.x, nullptr, &s.y_work, &s.e_work,
                 &s.common);
  if (s.x == nullptr || s.common.status < CHOLMOD_OK) throw RunFailure("CHOLMOD solve failed");
  const auto* solution = static_cast<const double*>(s.x->x);
  std::copy(solution, solution + n, x);
}

}  // namespace rockdd

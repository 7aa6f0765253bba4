#include "engine/solver/cholmod_solver.hpp"

#include <amd.h>
#include <cholmod.h>
#include <malloc.h>
#include <metis.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/common/errors.hpp"
#include "engine/solver/cholmod_statistics_clock.hpp"
#include "engine/solver/serial_openmp_regions.hpp"

#ifndef ROCKDD_SOLVER_CODE_HASH
#error "ROCKDD_SOLVER_CODE_HASH: the build's hash of engine/solver (engine/solver/CMakeLists.txt)"
#endif

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
/// heap lets the next factorization reuse the same memory. The heap is never trimmed either:
/// a factor that updates turned simplicial is freed whole at the next factorization (1.3 GB at
/// 1e6 dofs), and with a 1 GiB trim threshold that memory went back to the system and was
/// page-faulted in again by the new factor and the next conversion (conversion 0.4-1.3 s
/// instead of 0.17 s, factorization 2.3-2.6 s instead of 1.7-1.9 s). Done once per process.
void keep_large_blocks_in_heap() {
  static const bool done = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, -1);
    return true;
  }();
  (void)done;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// update_expected_faster() takes one refactorization to cost as much as
/// kBreakEvenPerRootN * sqrt(n) + kBreakEvenSmall / sqrt(n) update columns, and a conversion
/// to simplicial form kConversionPerFactor refactorizations: measured by bench_open_close on
/// 2D CST meshes, break-even at 85, 150 and 450 columns at 1e4, 1e5 and 1e6 dofs, which the
/// two terms meet within 3 % (docs/benchmarks.md). The second term is what a factorization
/// costs beyond its supernodes' flops at small sizes, where 0.5 sqrt(n) alone took 50
/// columns for 85. Below kSmallestFitted dofs (half the smallest size measured) nothing was
/// measured: the second term keeps its value there instead of growing without bound.
constexpr double kBreakEvenPerRootN = 0.45;
constexpr double kBreakEvenSmall = 4000.0;
constexpr double kSmallestFitted = 5e3;
constexpr double kConversionPerFactor = 0.15;

/// CHOLMOD's own test of a poor AMD ordering (cholmod_analyze.c, default strategy): at least
/// 500 flops per nonzero of L and a fill ratio nnz(L) / nnz(tril(A)) of at least 5. Only then
/// is nested dissection, far slower to compute, worth trying.
bool amd_fills_badly(double flops, double factor_nonzeros, double matrix_nonzeros) {
  return flops >= 500.0 * factor_nonzeros && factor_nonzeros >= 5.0 * matrix_nonzeros;
}

/// A system factorized many times tries the dissection by coordinates when AMD's factor needs
/// at least this many flops an equation. The dissection costs 0.6-1.3 us an equation (node
/// graph, cuts, CAMD and the analysis of its order), and a factorization at 10^4 dofs runs at
/// 3-6 GFLOP/s: from 10^4 flops an equation a factorization costs about twice as much, and
/// the dissection took 37-57 % off AMD's flops on the disk meshes (docs/performance.md, "Nested
/// dissection by coordinates"), paid back within a few factorizations. The compression
/// specimen's AMD factors (2.2k flops an equation, 123 analyses a realization) are not tried:
/// there AMD's factor is the smaller. A system factorized once tries it only where AMD fills
/// badly, as METIS before it: at 18k equations the dissection cost the one factorization more
/// than it saved.
constexpr double kDissectionWorthFlops = 1e4;

/// A CHOLMOD header over packed, sorted CSC arrays of ours, read in place (CHOLMOD only reads
/// them): `x` null for a pattern; stype 1 upper, -1 lower triangle, 0 unsymmetric.
cholmod_sparse csc_header(std::size_t nrow, std::size_t ncol, std::size_t nnz,
                          const std::int32_t* p, const std::int32_t* i, const double* x,
                          int stype) {
  cholmod_sparse a{};
  a.nrow = nrow;
  a.ncol = ncol;
  a.nzmax = nnz;
  a.p = const_cast<std::int32_t*>(p);
  a.i = const_cast<std::int32_t*>(i);
  a.x = const_cast<double*>(x);
  a.stype = stype;
  a.itype = CHOLMOD_INT;
  a.xtype = x != nullptr ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

/// A CHOLMOD header over a pattern's upper triangle.
cholmod_sparse upper_header(const SparsityPattern& pattern) {
  const auto n = static_cast<std::size_t>(pattern.n);
  return csc_header(n, n, static_cast<std::size_t>(pattern.nnz()), pattern.col_ptr.data(),
                    pattern.row_idx.data(), nullptr, 1);
}

}  // namespace

struct CholmodSolver::State {
  cholmod_common common{};
  std::int32_t n = 0;
  cholmod_factor* symbolic = nullptr;  // supernodal symbolic factor from the analysis
  cholmod_factor* factor = nullptr;    // numeric: supernodal LL^T, or simplicial LDL^T
  bool factor_ready = false;           // factor holds a usable factorization
  cholmod_dense* x = nullptr;
  cholmod_dense* y_work = nullptr;
  cholmod_dense* e_work = nullptr;
  cholmod_dense rhs{};
  int blas_threads = 1;
  // The factor's ordering P, applied here rather than by CHOLMOD: perm[k] is the equation of
  // the factor's column k, inverse_perm its inverse. Given A's upper triangle, CHOLMOD's
  // supernodal factorization would build tril(P A P^T) with cholmod_transpose at every
  // call; the analysis computes its pattern once, with the pattern index of each entry
  // (lower_source), and factorize() only gathers the values into it.
  std::vector<std::int32_t> perm, inverse_perm;
  std::vector<std::int32_t> lower_p, lower_i, lower_source;
  std::vector<double> lower_x, permuted;
  cholmod_sparse lower{};
  // Low-rank updates: C in CSC with its rows permuted (cholmod_updown works in the factor's
  // ordering).
  std::vector<std::int32_t> c_p, c_i, unordered_p, unordered_i, first_row, column_order;
  std::vector<double> c_x, unordered_x;
  std::vector<std::pair<std::int32_t, double>> entries;
  std::vector<std::uint32_t> visited;  // per column of L: stamp of the last downdate check
  std::uint32_t stamp = 0;

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
    cholmod_free_factor(&symbolic, &common);
    cholmod_finish(&common);
  }

  /// The supernodal symbolic factor of the pattern for a given ordering, or by CHOLMOD's own
  /// `method` (CHOLMOD_AMD; -1: its default strategy) when none is given; nullptr when the
  /// analysis fails.
  cholmod_factor* analyze_with(const SparsityPattern& pattern, std::int32_t* given, int method) {
    cholmod_sparse a = upper_header(pattern);
    common.nmethods = given == nullptr && method < 0 ? 0 : 1;
    common.method[0].ordering = given != nullptr ? CHOLMOD_GIVEN : method;
    return cholmod_analyze_p(&a, given, nullptr, 0, &common);
  }

  /// Builds tril(P A P^T) from A's upper triangle. Bucketing the entries by row, then
  /// reading the buckets in row order into their columns, leaves each column sorted.
  void build_permuted_lower(const SparsityPattern& pattern) {
    const std::int64_t nnz = pattern.nnz();
    std::vector<std::int32_t> row_start(static_cast<std::size_t>(n) + 1, 0);
    lower_p.assign(static_cast<std::size_t>(n) + 1, 0);
    for (std::int32_t c = 0; c < n; ++c)
      for (std::int32_t q = pattern.col_ptr[c]; q < pattern.col_ptr[c + 1]; ++q) {
        const std::int32_t a = inverse_perm[pattern.row_idx[q]], b = inverse_perm[c];
        ++row_start[std::max(a, b) + 1];
        ++lower_p[std::min(a, b) + 1];
      }
    for (std::int32_t k = 0; k < n; ++k) {
      row_start[k + 1] += row_start[k];
      lower_p[k + 1] += lower_p[k];
    }
    std::vector<std::int32_t> by_row_col(static_cast<std::size_t>(nnz));
    std::vector<std::int32_t> by_row_source(static_cast<std::size_t>(nnz));
    std::vector<std::int32_t> next(row_start.begin(), row_start.end() - 1);
    for (std::int32_t c = 0; c < n; ++c)
      for (std::int32_t q = pattern.col_ptr[c]; q < pattern.col_ptr[c + 1]; ++q) {
        const std::int32_t a = inverse_perm[pattern.row_idx[q]], b = inverse_perm[c];
        const std::int32_t slot = next[std::max(a, b)]++;
        by_row_col[slot] = std::min(a, b);
        by_row_source[slot] = q;
      }
    lower_i.resize(static_cast<std::size_t>(nnz));
    lower_source.resize(static_cast<std::size_t>(nnz));
    lower_x.assign(static_cast<std::size_t>(nnz), 0.0);
    next.assign(lower_p.begin(), lower_p.end() - 1);
    for (std::int32_t r = 0; r < n; ++r)
      for (std::int32_t q = row_start[r]; q < row_start[r + 1]; ++q) {
        const std::int32_t slot = next[by_row_col[q]]++;
        lower_i[slot] = r;
        lower_source[slot] = by_row_source[q];
      }
    // Lower triangle, in the factor's ordering: CHOLMOD reads it as it is.
    lower = csc_header(static_cast<std::size_t>(n), static_cast<std::size_t>(n),
                       static_cast<std::size_t>(nnz), lower_p.data(), lower_i.data(),
                       lower_x.data(), -1);
  }

  /// Builds P C in c_p/c_i/c_x: each column's rows mapped through the inverse permutation,
  /// sorted, repeated rows summed, prescribed (negative) rows and empty columns dropped; the
  /// columns ordered by their first row, so that the (up to 8) columns CHOLMOD takes per pass
  /// start close together in the elimination tree and share most of their paths to the root.
  void permute_terms(const LowRankTerms& terms) {
    const std::int32_t k = terms.num_columns();
    unordered_p.assign(1, 0);
    unordered_i.clear();
    unordered_x.clear();
    first_row.clear();
    for (std::int32_t j = 0; j < k; ++j) {
      entries.clear();
      for (std::int32_t q = terms.col_ptr[j]; q < terms.col_ptr[j + 1]; ++q) {
        const std::int32_t r = terms.row[q];
        if (r < 0) continue;
        if (r >= n)
          throw std::invalid_argument("LowRankTerms: equation " + std::to_string(r) +
                                      " out of range (n = " + std::to_string(n) + ")");
        entries.emplace_back(inverse_perm[r], terms.value[q]);
      }
      if (entries.empty()) continue;
      std::sort(entries.begin(), entries.end(),
                [](const auto& a, const auto& b) { return a.first < b.first; });
      first_row.push_back(entries.front().first);
      for (std::size_t e = 0; e < entries.size(); ++e) {
        if (e > 0 && entries[e].first == entries[e - 1].first) {
          unordered_x.back() += entries[e].second;
          continue;
        }
        unordered_i.push_back(entries[e].first);
        unordered_x.push_back(entries[e].second);
      }
      unordered_p.push_back(static_cast<std::int32_t>(unordered_i.size()));
    }
    const auto columns = static_cast<std::int32_t>(first_row.size());
    column_order.resize(static_cast<std::size_t>(columns));
    for (std::int32_t j = 0; j < columns; ++j) column_order[j] = j;
    std::stable_sort(column_order.begin(), column_order.end(),
                     [&](std::int32_t a, std::int32_t b) { return first_row[a] < first_row[b]; });
    c_p.assign(1, 0);
    c_i.clear();
    c_x.clear();
    for (const std::int32_t j : column_order) {
      c_i.insert(c_i.end(), unordered_i.begin() + unordered_p[j],
                 unordered_i.begin() + unordered_p[j + 1]);
      c_x.insert(c_x.end(), unordered_x.begin() + unordered_p[j],
                 unordered_x.begin() + unordered_p[j + 1]);
      c_p.push_back(static_cast<std::int32_t>(c_i.size()));
    }
  }

  /// After a downdate: the first column j of D <= 0 on the paths that C touched (from each
  /// column's first row up the elimination tree to the root), or -1. cholmod_updown itself
  /// does not report a downdate that loses positive definiteness.
  std::int32_t first_nonpositive_pivot() {
    const auto* lp = static_cast<const std::int32_t*>(factor->p);
    const auto* li = static_cast<const std::int32_t*>(factor->i);
    const auto* lnz = static_cast<const std::int32_t*>(factor->nz);
    const auto* lx = static_cast<const double*>(factor->x);
    if (visited.size() != factor->n) visited.assign(factor->n, 0);
    if (++stamp == 0) {
      std::fill(visited.begin(), visited.end(), 0);
      stamp = 1;
    }
    std::int32_t worst = -1;
    for (std::size_t c = 0; c + 1 < c_p.size(); ++c) {
      for (std::int32_t j = c_i[c_p[c]]; j >= 0 && visited[j] != stamp;
           j = lnz[j] > 1 ? li[lp[j] + 1] : -1) {
        visited[j] = stamp;
        if (!(lx[lp[j]] > 0.0) && (worst < 0 || j < worst)) worst = j;
      }
    }
    return worst;
  }
};

CholmodSolver::CholmodSolver(FillOrdering ordering)
    : state_(std::make_unique<State>()), ordering_(ordering) {
  keep_large_blocks_in_heap();
}
CholmodSolver::~CholmodSolver() = default;

bool CholmodSolver::analyzed() const {
  return state_->symbolic != nullptr;
}

bool CholmodSolver::supernodal() const {
  return state_->factor != nullptr && state_->factor->is_super;
}

void CholmodSolver::analyze(const SparsityPattern& pattern, std::span<const double> equation_xy,
                            OrderingEffort effort) {
  State& s = *state_;
  SerialOpenMpRegions serial;
  const auto start = std::chrono::steady_clock::now();
  cholmod_free_factor(&s.factor, &s.common);
  cholmod_free_factor(&s.symbolic, &s.common);
  s.factor_ready = false;
  s.n = pattern.n;
  FillOrdering kept = ordering_;
  if (ordering_ == FillOrdering::cholmod || ordering_ == FillOrdering::cholmod_amd) {
    s.symbolic =
        s.analyze_with(pattern, nullptr, ordering_ == FillOrdering::cholmod ? -1 : CHOLMOD_AMD);
  } else if (ordering_ == FillOrdering::node) {
    // CHOLMOD's default strategy with its nested dissection moved to the node graph: AMD
    // first (CHOLMOD's own, on the dof graph: it merges the dofs of a node itself and costs
    // less than building the node graph), then nested dissections of the node graph, keeping
    // the smallest factor. CHOLMOD's METIS would build and compress the dof graph first. The
    // dissection by coordinates takes a third of METIS's time, for 1-5 % more flops on the disk
    // meshes and 3 % fewer on grids: a system factorized once takes it instead of METIS's.
    s.symbolic = s.analyze_with(pattern, nullptr, CHOLMOD_AMD);
    kept = FillOrdering::cholmod_amd;
    if (s.symbolic != nullptr) {
      const bool fills_badly =
          amd_fills_badly(s.common.fl, s.common.lnz, static_cast<double>(pattern.nnz()));
      const bool thorough = effort == OrderingEffort::thorough;
      std::vector<FillOrdering> dissections;
      if (!equation_xy.empty() &&
          (fills_badly || (thorough && s.common.fl >= kDissectionWorthFlops * pattern.n)))
        dissections.push_back(FillOrdering::node_geometric);
      if (fills_badly && (equation_xy.empty() || thorough))
        dissections.push_back(FillOrdering::node_metis);
      double best_fl = s.common.fl, best_lnz = s.common.lnz;
      for (const FillOrdering dissection : dissections) {
        std::vector<std::int32_t> given = node_graph_ordering(pattern, dissection, equation_xy);
        cholmod_factor* dissected = s.analyze_with(pattern, given.data(), -1);
        if (dissected != nullptr && s.common.lnz < best_lnz) {
          cholmod_free_factor(&s.symbolic, &s.common);
          s.symbolic = dissected;
          kept = dissection;
          best_fl = s.common.fl;
          best_lnz = s.common.lnz;
        } else {
          cholmod_free_factor(&dissected, &s.common);
        }
      }
      s.common.fl = best_fl;  // the kept analysis's figures, whatever the others' were
      s.common.lnz = best_lnz;
      s.common.status = CHOLMOD_OK;
    }
  } else {
    std::vector<std::int32_t> given = node_graph_ordering(pattern, ordering_, equation_xy);
    s.symbolic = s.analyze_with(pattern, given.data(), -1);
  }
  finish_analysis(pattern, kept, start);
}

void CholmodSolver::analyze_given(const SparsityPattern& pattern,
                                  std::span<const std::int32_t> perm, FillOrdering kept) {
  State& s = *state_;
  SerialOpenMpRegions serial;
  const auto start = std::chrono::steady_clock::now();
  if (perm.size() != static_cast<std::size_t>(pattern.n))
    throw std::invalid_argument("CholmodSolver::analyze_given: " + std::to_string(perm.size()) +
                                " entries for " + std::to_string(pattern.n) + " equations");
  std::vector<std::uint8_t> seen(perm.size(), 0);
  for (const std::int32_t e : perm) {
    if (e < 0 || e >= pattern.n || seen[e])
      throw std::invalid_argument("CholmodSolver::analyze_given: not a permutation");
    seen[e] = 1;
  }
  cholmod_free_factor(&s.factor, &s.common);
  cholmod_free_factor(&s.symbolic, &s.common);
  s.factor_ready = false;
  s.n = pattern.n;
  // The factor's own pattern, tril(P A P^T), is built first and analysed in its natural
  // order: CHOLMOD then permutes nothing (given P and A, it would build P A P^T twice, once for
  // the column counts and once for the supernodes). The order stored by an earlier analysis
  // was postordered then; postordering it again is the identity in exact arithmetic but need
  // not keep ties as they were, so it is skipped.
  s.perm.assign(perm.begin(), perm.end());
  s.inverse_perm.resize(static_cast<std::size_t>(pattern.n));
  for (std::int32_t k = 0; k < pattern.n; ++k) s.inverse_perm[s.perm[k]] = k;
  s.build_permuted_lower(pattern);
  const bool postorder = s.common.postorder;
  s.common.postorder = false;
  s.common.nmethods = 1;
  s.common.method[0].ordering = CHOLMOD_NATURAL;
  s.symbolic = cholmod_analyze(&s.lower, &s.common);
  s.common.postorder = postorder;
  finish_analysis(pattern, kept, start, true);
}

const std::vector<std::int32_t>& CholmodSolver::permutation() const {
  return state_->perm;
}

std::string CholmodSolver::ordering_key() const {
  int cholmod[3] = {0, 0, 0};
  cholmod_version(cholmod);
  return "ordering " + std::string(fill_ordering_name(ordering_)) + " cholmod " +
         std::to_string(cholmod[0]) + '.' + std::to_string(cholmod[1]) + '.' +
         std::to_string(cholmod[2]) + " amd " + std::to_string(AMD_MAIN_VERSION) + '.' +
         std::to_string(AMD_SUB_VERSION) + '.' + std::to_string(AMD_SUBSUB_VERSION) + " metis " +
         std::to_string(METIS_VER_MAJOR) + '.' + std::to_string(METIS_VER_MINOR) + '.' +
         std::to_string(METIS_VER_SUBMINOR) + " solver code " + ROCKDD_SOLVER_CODE_HASH;
}

void CholmodSolver::finish_analysis(const SparsityPattern& pattern, FillOrdering kept,
                                    std::chrono::steady_clock::time_point start,
                                    bool permuted_already) {
  State& s = *state_;
  if (s.symbolic == nullptr || s.common.status < CHOLMOD_OK)
    throw std::runtime_error("CHOLMOD analysis failed (status " + std::to_string(s.common.status) +
                             ")");
  // The analysis leaves the factorization's flop count in Common->fl.
  s.blas_threads = s.common.fl > kParallelBlasFlops ? openblas_get_num_threads() : 1;
  auto* perm = static_cast<std::int32_t*>(s.symbolic->Perm);
  if (!permuted_already) {
    s.perm.assign(perm, perm + pattern.n);
    s.inverse_perm.resize(static_cast<std::size_t>(pattern.n));
    for (std::int32_t k = 0; k < pattern.n; ++k) s.inverse_perm[s.perm[k]] = k;
    s.build_permuted_lower(pattern);
  }
  // The factor now describes P A P^T in its own numbering: CHOLMOD is told that its ordering
  // is the natural one, so that it factorizes the lower triangle as given (no transpose) and
  // solves without permuting; solve() applies P itself.
  for (std::int32_t k = 0; k < pattern.n; ++k) perm[k] = k;
  s.symbolic->ordering = CHOLMOD_NATURAL;
  s.permuted.resize(static_cast<std::size_t>(pattern.n));
  stats_.factor_nonzeros = s.common.lnz;
  stats_.analysis_flops = s.common.fl;
  stats_.ordering = kept;
  stats_.last_analysis_seconds = seconds_since(start);
  stats_.analysis_seconds += stats_.last_analysis_seconds;
  ++stats_.analyses;
}

void CholmodSolver::factorize(const double* values) {
  State& s = *state_;
  if (s.symbolic == nullptr) throw std::logic_error("CholmodSolver::factorize before analyze");
  SerialOpenMpRegions serial;
  StoppedCholmodClock no_statistics_clock;
  // No more BLAS threads than the run was given (--threads): TBB's limit in force now.
  const auto allowed = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  BlasThreads blas(std::max(1, std::min(s.blas_threads, allowed)));
  s.factor_ready = false;
  // A supernodal factor is refactorized in place. One that updates turned simplicial cannot
  // go back (CHOLMOD converts only symbolic factors to supernodal): start again from a copy
  // of the analysis, which is cheap next to the factorization.
  if (s.factor == nullptr || !s.factor->is_super) {
    cholmod_free_factor(&s.factor, &s.common);
    s.factor = cholmod_copy_factor(s.symbolic, &s.common);
    if (s.factor == nullptr) throw RunFailure("CHOLMOD: out of memory copying the analysis");
  }
  const auto start = std::chrono::steady_clock::now();
  const std::size_t nnz = s.lower_source.size();
  for (std::size_t k = 0; k < nnz; ++k) s.lower_x[k] = values[s.lower_source[k]];
  cholmod_factorize(&s.lower, s.factor, &s.common);
  stats_.last_factor_seconds = seconds_since(start);
  stats_.last_factor_flops = s.common.fl;
  ++stats_.factorizations;
  if (s.common.status == CHOLMOD_NOT_POSDEF) {
    throw RunFailure("the system matrix is not positive definite (CHOLMOD stopped at column " +
                     std::to_string(s.factor->minor) + " of " + std::to_string(s.n) +
                     "): a body is unrestrained or an element has lost its stiffness");
  }
  if (s.common.status < CHOLMOD_OK)
    throw RunFailure("CHOLMOD factorization failed (status " + std::to_string(s.common.status) +
                     ")");
  s.factor_ready = true;
}

void CholmodSolver::update(const LowRankTerms& terms, bool add) {
  State& s = *state_;
  if (!s.factor_ready) throw std::logic_error("CholmodSolver::update without a factorization");
  const bool consistent = !terms.col_ptr.empty() && terms.col_ptr.front() == 0 &&
                          terms.row.size() == terms.value.size() &&
                          static_cast<std::size_t>(terms.col_ptr.back()) == terms.row.size() &&
                          std::is_sorted(terms.col_ptr.begin(), terms.col_ptr.end());
  if (!consistent) throw std::invalid_argument("LowRankTerms: col_ptr, row and value disagree");
  const auto start = std::chrono::steady_clock::now();
  s.permute_terms(terms);
  const auto columns = static_cast<std::int32_t>(s.c_p.size()) - 1;
  if (columns == 0) return;
  SerialOpenMpRegions serial;
  if (s.factor->is_super) {
    // Simplicial LDL^T, packed, columns in order: the form cholmod_updown modifies in place
    // (it would convert any other form itself, to the same).
    if (!cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, s.factor, &s.common)) {
      s.factor_ready = false;
      throw RunFailure("CHOLMOD could not convert the factor for an update (status " +
                       std::to_string(s.common.status) + ")");
    }
    ++stats_.simplicial_conversions;
  }
  cholmod_sparse c = csc_header(static_cast<std::size_t>(s.n), static_cast<std::size_t>(columns),
                                s.c_i.size(), s.c_p.data(), s.c_i.data(), s.c_x.data(), 0);
  const int ok = cholmod_updown(add, &c, s.factor, &s.common);
  ++stats_.updates;
  stats_.updated_columns += columns;
  stats_.last_update_seconds = seconds_since(start);
  if (!ok || s.common.status < CHOLMOD_OK) {
    s.factor_ready = false;
    throw RunFailure("CHOLMOD update failed (status " + std::to_string(s.common.status) + ")");
  }
  if (!add) {
    const std::int32_t column = s.first_nonpositive_pivot();
    if (column >= 0) {
      s.factor_ready = false;
      throw RunFailure("the system matrix is not positive definite after a downdate (pivot " +
                       std::to_string(column) + " of " + std::to_string(s.n) + ")");
    }
  }
}

bool CholmodSolver::update_expected_faster(std::int64_t columns) const {
  const State& s = *state_;
  if (!s.factor_ready || stats_.factorizations == 0) return false;
  if (columns <= 0) return true;
  // In units of one refactorization. A model, not timings: the choice changes the result's
  // round-off, and the results must not depend on how busy the machine was.
  const double n = static_cast<double>(s.n);
  const double break_even =
      kBreakEvenPerRootN * std::sqrt(n) + kBreakEvenSmall / std::sqrt(std::max(n, kSmallestFitted));
  double cost = static_cast<double>(columns) / break_even;
  if (s.factor->is_super) cost += kConversionPerFactor;
  return cost < 1.0;
}

void CholmodSolver::solve(const double* b, double* x, int columns) {
  State& s = *state_;
  if (!s.factor_ready) throw std::logic_error("CholmodSolver::solve without a factorization");
  if (columns < 1) throw std::invalid_argument("CholmodSolver::solve: columns must be >= 1");
  SerialOpenMpRegions serial;
  // One BLAS thread: a solve is too little work to share, and a woken OpenBLAS worker then
  // spins in sched_yield on the other core long after it (44 % of a 1-thread static solve's
  // samples). Also keeps the solve's rounding independent of OpenBLAS's thread count.
  BlasThreads blas(1);
  const auto n = static_cast<std::size_t>(s.n);
  const auto m = static_cast<std::size_t>(columns);
  if (s.permuted.size() < n * m) s.permuted.resize(n * m);
  for (std::size_t j = 0; j < m; ++j)  // b may alias x
    for (std::size_t k = 0; k < n; ++k) s.permuted[j * n + k] = b[j * n + s.perm[k]];
  s.rhs.nrow = n;
  s.rhs.ncol = m;
  s.rhs.nzmax = n * m;
  s.rhs.d = n;
  s.rhs.x = s.permuted.data();
  s.rhs.z = nullptr;
  s.rhs.xtype = CHOLMOD_REAL;
  s.rhs.dtype = CHOLMOD_DOUBLE;
  // cholmod_solve2 reuses x and the workspaces across calls: no allocation per solve. It
  // takes either form of the factor.
  cholmod_solve2(CHOLMOD_A, s.factor, &s.rhs, nullptr, &s.x, nullptr, &s.y_work, &s.e_work,
                 &s.common);
  if (s.x == nullptr || s.common.status < CHOLMOD_OK) throw RunFailure("CHOLMOD solve failed");
  const auto* solution = static_cast<const double*>(s.x->x);
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t k = 0; k < n; ++k) x[j * n + s.perm[k]] = solution[j * n + k];
}

}  // namespace rockdd

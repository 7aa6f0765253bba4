// CHOLMOD's statistics clock (engine/solver/cholmod_statistics_clock): stopped, CHOLMOD's
// supernodal factorization still counts its BLAS calls but reads no time for them, and the
// factor is the same to the bit; elsewhere the clock runs.
#include <gtest/gtest.h>

#include <cholmod.h>

#include <bit>
#include <cstdint>
#include <thread>
#include <vector>

#include "engine/solver/cholmod_statistics_clock.hpp"

extern "C" double SuiteSparse_time(void);

namespace rockdd {
namespace {

TEST(CholmodStatisticsClock, ReadsZeroOnlyWhileStoppedOnThisThread) {
  EXPECT_GT(SuiteSparse_time(), 0.0);
  {
    const StoppedCholmodClock stopped;
    EXPECT_EQ(SuiteSparse_time(), 0.0);
    {
      const StoppedCholmodClock nested;
      EXPECT_EQ(SuiteSparse_time(), 0.0);
    }
    EXPECT_TRUE(StoppedCholmodClock::active());  // the inner scope restores the outer one's
    // Another thread (a library user's, a TBB worker) keeps SuiteSparse's clock.
    double elsewhere = 0.0;
    std::thread([&] { elsewhere = SuiteSparse_time(); }).join();
    EXPECT_GT(elsewhere, 0.0);
  }
  EXPECT_FALSE(StoppedCholmodClock::active());
  EXPECT_GT(SuiteSparse_time(), 0.0);
}

/// The 5-point Laplacian of an m x m grid plus the identity, lower triangle, CHOLMOD's form.
cholmod_sparse* grid_laplacian(int m, cholmod_common* common) {
  const int n = m * m;
  cholmod_sparse* a = cholmod_allocate_sparse(n, n, 3 * n, 1, 1, -1, CHOLMOD_REAL, common);
  auto* p = static_cast<int*>(a->p);
  auto* i = static_cast<int*>(a->i);
  auto* x = static_cast<double*>(a->x);
  int k = 0;
  for (int col = 0; col < n; ++col) {
    p[col] = k;
    i[k] = col, x[k++] = 5.0;
    if ((col + 1) % m != 0) i[k] = col + 1, x[k++] = -1.0;
    if (col + m < n) i[k] = col + m, x[k++] = -1.0;
  }
  p[n] = k;
  return a;
}

TEST(CholmodStatisticsClock, StoppedFactorizationCountsItsBlasCallsButReadsNoTime) {
  // The interposer must reach CHOLMOD's calls in a program linked as rockdd is: with the clock
  // stopped, CHOLMOD_CPU_SYRK_CALLS and CHOLMOD_CPU_GEMM_CALLS grow while their times stay 0;
  // running, the times grow. The factor is the same to the bit either way.
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse* a = grid_laplacian(120, &common);
  cholmod_factor* stopped_factor = cholmod_analyze(a, &common);
  cholmod_factor* running_factor = cholmod_analyze(a, &common);
  ASSERT_NE(stopped_factor, nullptr);
  {
    const StoppedCholmodClock stopped;
    cholmod_factorize(a, stopped_factor, &common);
  }
  ASSERT_EQ(common.status, CHOLMOD_OK);
  ASSERT_TRUE(stopped_factor->is_super);
  EXPECT_GT(common.CHOLMOD_CPU_SYRK_CALLS + common.CHOLMOD_CPU_GEMM_CALLS, 0);
  EXPECT_EQ(common.CHOLMOD_CPU_SYRK_TIME, 0.0);
  EXPECT_EQ(common.CHOLMOD_CPU_GEMM_TIME, 0.0);
  EXPECT_EQ(common.CHOLMOD_CPU_POTRF_TIME, 0.0);
  EXPECT_EQ(common.CHOLMOD_CPU_TRSM_TIME, 0.0);

  cholmod_factorize(a, running_factor, &common);
  ASSERT_EQ(common.status, CHOLMOD_OK);
  EXPECT_GT(common.CHOLMOD_CPU_SYRK_TIME + common.CHOLMOD_CPU_GEMM_TIME +
                common.CHOLMOD_CPU_POTRF_TIME + common.CHOLMOD_CPU_TRSM_TIME,
            0.0);
  ASSERT_EQ(stopped_factor->xsize, running_factor->xsize);
  const auto* x0 = static_cast<const double*>(stopped_factor->x);
  const auto* x1 = static_cast<const double*>(running_factor->x);
  std::size_t differing = 0;
  for (std::size_t k = 0; k < stopped_factor->xsize; ++k)
    differing += std::bit_cast<std::uint64_t>(x0[k]) != std::bit_cast<std::uint64_t>(x1[k]);
  EXPECT_EQ(differing, 0u);

  cholmod_free_factor(&stopped_factor, &common);
  cholmod_free_factor(&running_factor, &common);
  cholmod_free_sparse(&a, &common);
  cholmod_finish(&common);
}

}  // namespace
}  // namespace rockdd

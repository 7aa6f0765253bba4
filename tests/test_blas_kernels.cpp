// The choice of OpenBLAS's kernel set (engine/solver/blas_kernels): which fallbacks are
// replaced, and that this process's BLAS names the set it runs.
#include <gtest/gtest.h>

#include <cstdlib>

#include "engine/solver/blas_kernels.hpp"

namespace rockdd {
namespace {

constexpr CpuVectorFeatures kAvx2Fma{true, true};

TEST(BlasKernels, AFallbackOlderThanHaswellIsReplacedWhereTheCpuHasAvx2AndFma) {
  EXPECT_EQ(better_blas_kernel_set("Prescott", kAvx2Fma), "Haswell");
  EXPECT_EQ(better_blas_kernel_set("PRESCOTT", kAvx2Fma), "Haswell");
  EXPECT_EQ(better_blas_kernel_set("Nehalem", kAvx2Fma), "Haswell");
  EXPECT_EQ(better_blas_kernel_set("Sandybridge", kAvx2Fma), "Haswell");
  EXPECT_EQ(better_blas_kernel_set("Core2", kAvx2Fma), "Haswell");
  EXPECT_EQ(better_blas_kernel_set("Unknown", kAvx2Fma), "Haswell");
}

TEST(BlasKernels, ASetChosenByTheCpuModelIsKept) {
  for (const char* set :
       {"Haswell", "Zen", "SkylakeX", "Cooperlake", "SapphireRapids", "Excavator", "Bulldozer"})
    EXPECT_EQ(better_blas_kernel_set(set, kAvx2Fma), "") << set;
}

TEST(BlasKernels, NothingIsAskedOfACpuWithoutAvx2OrFma) {
  EXPECT_EQ(better_blas_kernel_set("Prescott", CpuVectorFeatures{true, false}), "");
  EXPECT_EQ(better_blas_kernel_set("Prescott", CpuVectorFeatures{false, true}), "");
  EXPECT_EQ(better_blas_kernel_set("Prescott", CpuVectorFeatures{}), "");
  EXPECT_EQ(better_blas_kernel_set("", kAvx2Fma), "");
}

TEST(BlasKernels, ThisProcessesOpenBlasNamesTheSetItRuns) {
  const std::string running = blas_kernel_set();
  ASSERT_FALSE(running.empty());
  // Where the environment names a set (as CTest's runs may inherit), OpenBLAS runs it.
  if (const char* asked = std::getenv(kBlasKernelSetVariable); asked != nullptr) {
    std::string a(asked), r(running);
    for (auto* s : {&a, &r})
      for (char& c : *s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(r, a);
  }
}

}  // namespace
}  // namespace rockdd

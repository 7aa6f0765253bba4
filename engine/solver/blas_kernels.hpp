#pragma once
// Which of OpenBLAS's kernel sets runs CHOLMOD's supernodes, and a better one where OpenBLAS
// could not name the CPU.
//
// OpenBLAS picks its kernel set once, as it loads, from the CPU's vendor, family and model. A
// CPU it does not know by model (a virtual machine reporting "Intel(R) Xeon(R) Processor"
// with AVX2, FMA and AVX-512) gets its oldest x86-64 set, Prescott (SSE3), whose dgemm and
// dtrsm ran CHOLMOD's factorization of 10^5 dofs 1.3-1.5x slower than the Haswell set that the
// CPU's features allow (docs/performance.md, "OpenBLAS's kernels on a CPU it cannot name").
// The set can only be chosen before OpenBLAS loads, through its own environment variable
// OPENBLAS_CORETYPE; `rockdd` and the benchmarks therefore start themselves again with it
// set, before any other work (restart_with_better_blas_kernels).

#include <string>
#include <string_view>

namespace rockdd {

/// The environment variable OpenBLAS reads its kernel set from as it loads.
inline constexpr const char* kBlasKernelSetVariable = "OPENBLAS_CORETYPE";

/// The name OpenBLAS gives the kernel set it runs ("Haswell", "Prescott").
std::string blas_kernel_set();

/// The CPU features that decide which of OpenBLAS's x86-64 kernel sets can run.
struct CpuVectorFeatures {
  bool avx2 = false;  ///< AVX2, with the operating system saving the AVX state
  bool fma = false;   ///< FMA3
};

/// This CPU's features (all false off x86-64).
CpuVectorFeatures cpu_vector_features();

/// The kernel set to ask OpenBLAS for instead of `running`, or empty to keep `running`:
/// "Haswell" where the CPU has AVX2 and FMA but OpenBLAS fell back to a set without AVX2
/// kernels. A set OpenBLAS chose by the CPU's model (Haswell, Zen, SkylakeX, ...) is kept.
std::string better_blas_kernel_set(std::string_view running, CpuVectorFeatures cpu);

/// Starts this program again (the same executable and arguments) with OPENBLAS_CORETYPE set
/// to better_blas_kernel_set's choice, where there is one. Call it first in main, before any
/// thread starts. Returns when no restart is wanted or it failed (the program then goes on
/// with OpenBLAS's choice); a set already in the environment, the user's or an earlier
/// restart's, is left as it is, and so is a process under valgrind.
void restart_with_better_blas_kernels(char** argv);

}  // namespace rockdd

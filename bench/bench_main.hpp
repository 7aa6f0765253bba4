#pragma once
// The main of the benchmarks that factorize or solve: OpenBLAS's kernels chosen as `rockdd`
// chooses them (engine/solver/blas_kernels.hpp), so that a benchmark times the kernels a run
// uses, then Google Benchmark's own main.

#include <benchmark/benchmark.h>

#include "engine/solver/blas_kernels.hpp"

namespace rockdd::bench {

inline int run_benchmarks(int argc, char** argv) {
  restart_with_better_blas_kernels(argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace rockdd::bench

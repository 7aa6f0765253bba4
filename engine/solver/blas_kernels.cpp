#include "engine/solver/blas_kernels.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

extern "C" {
char* openblas_get_corename(void);
}

namespace rockdd {

std::string blas_kernel_set() {
  const char* name = openblas_get_corename();
  return name != nullptr ? std::string(name) : std::string();
}

CpuVectorFeatures cpu_vector_features() {
  CpuVectorFeatures cpu;
#if defined(__x86_64__)
  __builtin_cpu_init();
  // GCC's test for AVX2 includes the operating system's saving of the AVX registers.
  cpu.avx2 = __builtin_cpu_supports("avx2") != 0;
  cpu.fma = __builtin_cpu_supports("fma") != 0;
#endif
  return cpu;
}

std::string better_blas_kernel_set(std::string_view running, CpuVectorFeatures cpu) {
  if (!cpu.avx2 || !cpu.fma || running.empty()) return {};
  // OpenBLAS's x86-64 sets without AVX2 kernels that it also takes as fallbacks: Prescott for
  // a CPU it cannot name, the others for old models. AMD's Bulldozer line and every set
  // from Haswell on are chosen by model and kept.
  static constexpr std::array<std::string_view, 18> kOlderThanHaswell = {
      "unknown", "katmai",       "coppermine", "northwood",  "prescott", "banias",
      "atom",    "core2",        "penryn",     "dunnington", "nehalem",  "athlon",
      "opteron", "opteron_sse3", "barcelona",  "nano",       "bobcat",   "sandybridge"};
  std::string name(running);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool older = std::find(kOlderThanHaswell.begin(), kOlderThanHaswell.end(), name) !=
                     kOlderThanHaswell.end();
  return older ? std::string("Haswell") : std::string();
}

namespace {

/// Whether this process runs under valgrind, whose launcher preloads its vgpreload libraries:
/// an exec there leaves valgrind (without --trace-children), and callgrind's counts
/// (tools/bench-track) would stop at the restart.
bool under_valgrind() {
  const char* preload = std::getenv("LD_PRELOAD");
  return preload != nullptr && std::strstr(preload, "vgpreload") != nullptr;
}

}  // namespace

void restart_with_better_blas_kernels(char** argv) {
  if (std::getenv(kBlasKernelSetVariable) != nullptr || under_valgrind()) return;
  const std::string better = better_blas_kernel_set(blas_kernel_set(), cpu_vector_features());
  if (better.empty()) return;
  // The executable's own path rather than /proc/self/exe, so that ps and top keep its name.
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return;
  ::setenv(kBlasKernelSetVariable, better.c_str(), 1);
  ::execv(exe.c_str(), argv);
  ::unsetenv(kBlasKernelSetVariable);
}

}  // namespace rockdd

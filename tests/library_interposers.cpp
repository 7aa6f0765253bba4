// A program linked to librockdd.so, as a library user's is: CHOLMOD's calls to the entry point
// named on the command line must reach rockdd's definition, not the system library's.
//  - GOMP_parallel (engine/solver/serial_openmp_regions): when the library hid it, CHOLMOD
//    factorized 5x slower in library and Python callers than in `rockdd run` (the paper's UCS
//    to 20 % softening: 25.3 s of factorization against 5.3 s).
//  - SuiteSparse_time (engine/solver/cholmod_statistics_clock): CHOLMOD's statistics clock,
//    2.3 % of perf's samples in a compression realization.
#include <dlfcn.h>

#include <cstdio>
#include <cstring>

#include <rockdd/rockdd.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::printf("usage: library_interposers SYMBOL\n");
    return 2;
  }
  const char* symbol = argv[1];
  std::printf("rockdd %s\n", rockdd::api::version());  // keeps the library linked
  void* entry = dlsym(RTLD_DEFAULT, symbol);
  Dl_info info{};
  if (entry == nullptr || dladdr(entry, &info) == 0 || info.dli_fname == nullptr) {
    std::printf("%s not found\n", symbol);
    return 1;
  }
  std::printf("%s resolves to %s\n", symbol, info.dli_fname);
  return std::strstr(info.dli_fname, "librockdd") != nullptr ? 0 : 1;
}

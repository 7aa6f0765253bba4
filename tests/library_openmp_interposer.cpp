// A program linked to librockdd.so, as a library user's is: CHOLMOD's OpenMP regions must
// reach rockdd's GOMP_parallel (engine/solver/serial_openmp_regions), not libgomp's. When the
// library hid it, CHOLMOD factorized 5x slower in library and Python callers than in
// `rockdd run` (the paper's UCS to 20 % softening: 25.3 s of factorization against 5.3 s).
#include <dlfcn.h>

#include <cstdio>
#include <cstring>

#include <rockdd/rockdd.hpp>

int main() {
  std::printf("rockdd %s\n", rockdd::api::version());  // keeps the library linked
  void* entry = dlsym(RTLD_DEFAULT, "GOMP_parallel");
  Dl_info info{};
  if (entry == nullptr || dladdr(entry, &info) == 0 || info.dli_fname == nullptr) {
    std::printf("GOMP_parallel not found\n");
    return 1;
  }
  std::printf("GOMP_parallel resolves to %s\n", info.dli_fname);
  return std::strstr(info.dli_fname, "librockdd") != nullptr ? 0 : 1;
}

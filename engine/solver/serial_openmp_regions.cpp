#include "engine/solver/serial_openmp_regions.hpp"

#include <dlfcn.h>

namespace rockdd {
namespace {

thread_local bool inline_regions = false;

}  // namespace

SerialOpenMpRegions::SerialOpenMpRegions() : previous_(inline_regions) {
  inline_regions = true;
}
SerialOpenMpRegions::~SerialOpenMpRegions() {
  inline_regions = previous_;
}
bool SerialOpenMpRegions::active() {
  return inline_regions;
}

}  // namespace rockdd

// libgomp's entry point for `#pragma omp parallel` (GCC >= 4.9 ABI). Defined here, it takes
// precedence over libgomp's for every library in the process; it forwards to libgomp's
// unless the calling thread asked for inline regions. Inline, the outlined body runs once on
// this thread, where omp_get_num_threads() = 1 and omp_get_thread_num() = 0, exactly as in
// a team of one. Exported from librockdd.so too (library/CMakeLists.txt links this file into
// it directly, since --exclude-libs hides every symbol of the static engine): without it,
// CHOLMOD in a library or Python caller's process took 5x as long to factorize.
extern "C" __attribute__((visibility("default"))) void GOMP_parallel(void (*fn)(void*), void* data,
                                                                     unsigned num_threads,
                                                                     unsigned flags) {
  if (rockdd::inline_regions) {
    fn(data);
    return;
  }
  using Entry = void (*)(void (*)(void*), void*, unsigned, unsigned);
  static const auto libgomp_parallel = reinterpret_cast<Entry>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  libgomp_parallel(fn, data, num_threads, flags);
}

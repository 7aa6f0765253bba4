#include "engine/solver/cholmod_statistics_clock.hpp"

#include <dlfcn.h>

namespace rockdd {
namespace {

thread_local bool stopped = false;

}  // namespace

StoppedCholmodClock::StoppedCholmodClock() : previous_(stopped) {
  stopped = true;
}
StoppedCholmodClock::~StoppedCholmodClock() {
  stopped = previous_;
}
bool StoppedCholmodClock::active() {
  return stopped;
}

}  // namespace rockdd

// SuiteSparse's clock (libsuitesparseconfig). Defined here, it takes precedence over the
// library's for every library in the process, as GOMP_parallel does
// (serial_openmp_regions.cpp); it forwards to SuiteSparse's unless the calling thread stopped
// the clock. Exported from librockdd.so too (library/CMakeLists.txt links this file into it
// directly).
extern "C" __attribute__((visibility("default"))) double SuiteSparse_time(void) {
  if (rockdd::stopped) return 0.0;
  using Entry = double (*)(void);
  static const auto suitesparse_time =
      reinterpret_cast<Entry>(dlsym(RTLD_NEXT, "SuiteSparse_time"));
  return suitesparse_time();
}

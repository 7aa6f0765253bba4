#pragma once
// Running CHOLMOD's OpenMP regions inline on the calling thread.
//
// Debian's CHOLMOD opens an OpenMP parallel region (with a num_threads clause) around small
// loops of every supernode. Even a region serialized by the OpenMP runtime ends with a
// barrier whose futex wake is a system call, and on these virtual machines a 2D factor with
// ~2,500 supernodes spent over half its time in those calls (measured with perf: 4.7e7
// flops took 38 ms). While a SerialOpenMpRegions is alive on a thread, parallel regions
// entered from that thread run as a plain call: same results (CHOLMOD's loops see one
// thread), no team, no barrier. Elsewhere, and on other threads, OpenMP is untouched.

namespace rockdd {

/// Scope in which OpenMP parallel regions opened by this thread run inline.
class SerialOpenMpRegions {
 public:
  SerialOpenMpRegions();
  ~SerialOpenMpRegions();
  SerialOpenMpRegions(const SerialOpenMpRegions&) = delete;
  SerialOpenMpRegions& operator=(const SerialOpenMpRegions&) = delete;

  /// Whether regions are inlined on this thread right now.
  static bool active();

 private:
  bool previous_;
};

}  // namespace rockdd

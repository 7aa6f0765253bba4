#pragma once
// Exclusive use of the process-wide Gmsh library, which is neither thread-safe nor re-entrant.
#include <functional>
#include <mutex>
#include <string>

namespace rockdd {

/// Holds Gmsh for one mesh: initializes it, quiet, and finalizes it when it goes out of scope,
/// so that no option or model state of one mesh reaches the next.
/// Gmsh sets the process's OpenMP thread count (to 1) whenever it sets General.NumThreads,
/// at initialization too; the count the process had is restored on the way out.
/// `threads` is Gmsh's General.NumThreads. The engine meshes with 1: with 2, Gmsh 4.8 gave
/// different meshes from one run to the next (docs/meshing.md, tools/mesh_study), and a run's
/// results must not depend on its thread count; nor was there a gain to trade for it.
class GmshSession {
 public:
  explicit GmshSession(int threads = 1);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;  // first member: released after Gmsh is finalized
  int openmp_threads_ = 1;             // omp_get_max_threads() before Gmsh ran
};

/// Runs `step` (which calls Gmsh) with Gmsh's errors logged rather than thrown, and returns the
/// first error's text, "" if none. A throw inside Gmsh's OpenMP meshing loops aborts the
/// process, and one out of its .geo parser leaves the parser unusable for later files.
/// Call with a GmshSession held.
std::string first_gmsh_error(const std::function<void()>& step);

}  // namespace rockdd

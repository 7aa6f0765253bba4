#pragma once
// Meshing in a child process on a budget (issue 28). Gmsh reads and meshes in a fork of the
// process that wants the mesh, with its address space limited (RLIMIT_AS) and a time limit
// after which it is killed, and hands the mesh back through a pipe: whatever a .geo asks for
// (a size field of 1e-9 m, a transfinite curve of 1e12 nodes) or a .msh holds, and whatever
// Gmsh does with it (a crash, a hang, gigabytes), the asking process gets a mesh or an
// InputError, and the machine keeps its memory.
#include <functional>
#include <string>

#include "engine/mesh/mesh.hpp"
#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// Peak memory of Gmsh per triangle, bytes, doubled: its peak RSS grew by 740 bytes a
/// triangle from 258,000 to 1,030,000 triangles of a frontal-Delaunay square (242 and 813
/// MB; /usr/bin/time, Gmsh 4.8.4). A meshing process may take this much for every triangle
/// that the memory available allows a run (mesh_budget, 2,000 bytes a triangle), so it
/// stays below the memory available, however large its mesh.
constexpr double kMeshingBytesPerTriangle = 1500.0;

/// Address space a meshing process needs besides its mesh: the Gmsh module and the ~90
/// libraries it opens, and their reservations. Generous, never measured tight.
constexpr double kMeshingFixedBytes = 1024.0 * 1024 * 1024;

/// Time a meshing process may take per triangle the memory allows: docs/meshing.md measured
/// up to 570 us of CPU a triangle (Gmsh's packing algorithm, the slowest a .geo can choose;
/// frontal-Delaunay, the default, 25 to 71), rounded up.
constexpr double kMeshingSecondsPerTriangle = 6e-4;

/// The least time limit, s: small meshes start Gmsh and its libraries on a loaded machine.
constexpr double kLeastMeshingSeconds = 60.0;

/// What a meshing process may take.
struct MeshingLimits {
  double seconds = 0.0;  // wall-clock time, after which it is killed
  /// Memory beyond the asking process's own, bytes; 0: unlimited. Held twice: as address
  /// space (RLIMIT_AS: an allocation beyond it fails) and as resident memory, looked at
  /// every 0.1 s (beyond it the process is killed), which holds under AddressSanitizer too.
  double bytes = 0.0;
};

/// The limits for a mesh made now: kMeshingBytesPerTriangle and kMeshingSecondsPerTriangle
/// times the most triangles a run may have (mesh_budget: the memory available, at most
/// kMostTriangles), plus kMeshingFixedBytes, at least kLeastMeshingSeconds. The environment
/// variables ROCKDD_MESHING_SECONDS and ROCKDD_MESHING_BYTES (positive numbers) replace them.
MeshingLimits meshing_limits();

/// Runs `make` in a child process under `limits` and returns the mesh it made. An InputError
/// in the child is thrown here as it was; a child that runs past the time limit is killed, and
/// it, a child that runs out of memory and one that dies on a signal (a crash in Gmsh) become
/// an InputError through `source` that says so, naming `what` (the file or the shape). Other
/// exceptions of the child come back as std::runtime_error with their text.
/// Under AddressSanitizer, whose shadow memory needs terabytes of address space, only the
/// resident memory is limited.
Mesh mesh_in_child_process(const std::function<Mesh()>& make, const MeshingLimits& limits,
                           const MeshSource& source, const std::string& what);

}  // namespace rockdd

#pragma once
// How many triangles a mesh will have and whether a run on them fits in memory, known before
// Gmsh meshes anything: a scene that cannot fit is refused up front (exit 2) rather than
// meshed for minutes and killed by the kernel's OOM killer.
#include <optional>
#include <string>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// Peak memory of a run per triangle, bytes. Measured (peak RSS, /usr/bin/time -v) on static
/// runs of a 1 x 1 m rectangle fixed at the bottom and loaded on top, 2 threads:
///   divisions [150, 150]: 45,000 triangles 110 MiB; [300, 300]: 180,000, 306 MiB;
///   [450, 450]: 405,000, 615 MiB (1,520 and 1,440 bytes a triangle between them);
///   element_size 7.16e-3: 45,436 triangles 129 MiB; 3.58e-3: 181,612, 381 MiB
///   (1,940 bytes a triangle: the unstructured mesh's factor fills in more).
/// Rounded up from the larger; about 46 MiB of libraries come on top of it.
constexpr double kBytesPerTriangle = 2000.0;

/// Most triangles of any mesh, memory allowing: beyond it Gmsh takes many minutes, and
/// a scene asking for more than that has a typo in its sizes.
constexpr double kMostTriangles = 5e7;

/// Triangles of an equilateral mesh of size `element_size` over `area`: area / (sqrt(3)/4 h^2).
double triangles_over_area(double area, double element_size);

/// The triangles of a built-in shape: exact for a rectangle's divisions, estimated from the
/// area for element_size; nullopt for .geo and .msh files (known once Gmsh has them).
std::optional<double> estimated_triangles(const MeshSpec& mesh);

/// Bytes the system can still give this process: MemAvailable of /proc/meminfo, else the free
/// physical pages (sysconf).
double available_memory_bytes();

/// A count for messages: "20000000000" up to 1e15, then "2e+20".
std::string count_text(double count);

/// The expectation a mesh of `triangles` (estimated, or a lower bound when `at_least`) fails
/// with `available` bytes left ("expected ..., got ..."), or "" when it fits.
std::string mesh_budget_problem(double triangles, double available, bool at_least = false);

}  // namespace rockdd

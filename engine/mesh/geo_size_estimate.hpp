#pragma once
// How many segments Gmsh's 1D mesher will put on the curves of a .geo, known before it meshes:
// a size of 1e-9 at a point of a 25 mm disk asked Gmsh for 1.6e8 nodes on each arc, and it
// grew by 60 MB/s until the machine ran out of memory (issue 28).
#include <filesystem>

namespace rockdd {

/// A lower bound on the segments of the 1D mesh of the current Gmsh model (a .geo just read,
/// its options set): per curve, its transfinite count when it has one, else the integral of
/// 1 / size along it, where the size is Gmsh's: the sizes at the curve's end points
/// interpolated along its parameter (Mesh.MeshSizeFromPoints), or the model's size without
/// them, no more than Mesh.MeshSizeMax and 2 pi / (curvature x Mesh.MeshSizeFromCurvature),
/// no less than Mesh.MeshSizeMin, times Mesh.MeshSizeFactor. Size fields and callbacks can
/// only make sizes smaller (Gmsh takes the least of all sizes), so leaving them out keeps the
/// bound a lower one. The point sizes and transfinite counts, which the API of Gmsh 4.8 does
/// not give, are read from the model written as a .geo_unrolled file in `scratch_dir`.
/// Call with a GmshSession held.
double geo_curve_segments_at_least(const std::filesystem::path& scratch_dir);

}  // namespace rockdd

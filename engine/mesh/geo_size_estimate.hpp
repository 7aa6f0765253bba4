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

/// What the curves' mesh says of the surfaces' before Gmsh meshes them: once it has meshed the
/// curves of the current model (generate(1), size fields included), a lower bound on its
/// triangles: the area of its surfaces (from their meshed boundaries) over that of an
/// equilateral triangle of 1.5 times the longest segment. Inside a surface Gmsh's sizes come
/// from its boundary's (Mesh.MeshSizeExtendFromBoundary; else from the model's size and
/// Mesh.MeshSizeMax), fields and caps only make them smaller, and its edges stay within about
/// 1.4 sizes: no triangle is larger. `longest` is set to that segment. Call with a
/// GmshSession held.
double geo_triangles_at_least(double& longest);

}  // namespace rockdd

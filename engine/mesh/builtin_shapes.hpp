#pragma once
// The built-in shapes of a scene's [mesh] (shape = "rectangle" | "disk"), drawn in Gmsh.
#include "engine/mesh/mesh_errors.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Adds the rectangle of `spec` to the current Gmsh model, ready for 2D meshing: structured
/// (spec.divisions cells, two triangles a cell, alternating diagonals) unless element_size is
/// given, then unstructured. Names: body "body"; curves "bottom", "right", "top", "left";
/// points "bottom_left", "bottom_right", "top_right", "top_left".
void add_rectangle(const MeshSpec& spec, const MeshSource& source);

/// Adds the disk of `spec` (centre spec.origin) to the current Gmsh model, its top and bottom
/// cut flat by chords at y = ±R cos(alpha), alpha = flat_half_angle_deg. Names: body "body";
/// curves "top_flat", "bottom_flat" (when alpha > 0) and "rim" (both arcs); points "center",
/// "top", "bottom" (midpoints of the flats, or (0, ±R) when alpha = 0), "left", "right"
/// ((∓R, 0)), all of them mesh nodes.
void add_disk(const MeshSpec& spec, const MeshSource& source);

}  // namespace rockdd

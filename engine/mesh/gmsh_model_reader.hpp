#pragma once
// Reading the current Gmsh model's 2D mesh and physical groups into plain arrays.
#include "engine/mesh/mesh_errors.hpp"
#include "engine/mesh/tagged_mesh.hpp"

namespace rockdd {

/// The triangles of every surface entity, all nodes Gmsh holds (used or not, in Gmsh's order),
/// and the named physical groups: surfaces → bodies, curves → line-element edges, points →
/// nodes. Unnamed physical curves and points are left out. Node numbers are positions in
/// Gmsh's node list; triangles keep Gmsh's orientation. Call with a GmshSession held.
/// Throws InputError for elements other than 3-node triangles, lines and points.
TaggedMesh read_gmsh_model(const MeshSource& source);

}  // namespace rockdd

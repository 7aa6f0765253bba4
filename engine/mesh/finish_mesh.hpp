#pragma once
// Turning the raw mesh Gmsh holds into the compact, oriented mesh the engine uses.
#include "engine/mesh/mesh_errors.hpp"
#include "engine/mesh/tagged_mesh.hpp"

namespace rockdd {

/// Keeps only the nodes on triangles and renumbers them 0..n-1 by reverse Cuthill–McKee;
/// sorts elements by their lowest node (stable); turns every triangle counter-clockwise;
/// maps curve edges to node pairs along triangle sides (a boundary edge runs counter-clockwise
/// around its triangle, so the material lies on its left) without repeats, and point nodes to
/// sorted unique ids. Throws InputError naming a physical curve or point whose nodes are on no
/// triangle, or whose edge is no triangle's side.
TaggedMesh finish_mesh(const TaggedMesh& raw, const MeshSource& source);

}  // namespace rockdd

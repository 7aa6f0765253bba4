#pragma once
// Mesh checks that name elements the way their source numbers them.
#include <cstddef>
#include <span>

#include "engine/mesh/mesh.hpp"
#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// validate_mesh, with element e called `element_labels[e]` in messages (its Gmsh tag);
/// with no labels, elements are called by their index.
void validate_mesh(const Mesh& mesh, const MeshSource& source,
                   std::span<const std::size_t> element_labels);

}  // namespace rockdd

#pragma once
// A mesh together with the element numbers its source uses, so messages name elements as the
// user sees them (Gmsh element tags), whatever order the engine keeps them in.
#include <cstddef>
#include <vector>

#include "engine/mesh/mesh.hpp"

namespace rockdd {

/// `mesh` plus, per element, the number its source gave it.
struct TaggedMesh {
  Mesh mesh;
  std::vector<std::size_t> element_tags;
};

}  // namespace rockdd

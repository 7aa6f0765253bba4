#pragma once
// The $PhysicalNames sections of a `mesh.msh` file, checked before Gmsh is given it.
#include <filesystem>

#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// Throws InputError (through `source`) unless every $PhysicalNames section of `file` holds
/// its count, then that many lines "<dim> <tag> \"<name>\"" with dim in 0..3, a positive tag
/// and a quoted name of printable characters, then $EndPhysicalNames.
void check_msh_physical_names(const std::filesystem::path& file, const MeshSource& source);

}  // namespace rockdd

#pragma once
// The header a `mesh.msh` file must start with before Gmsh is given it.
#include <filesystem>

#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// Throws InputError (through `source`) unless `file` starts with a $MeshFormat line followed
/// by "<version> <file-type> <data-size>": version 2.x or 4.x (docs/scene.md: formats 2.2 and 4.1),
/// file-type 0 (ASCII) or 1 (binary), data-size 8 (Gmsh reads 8-byte doubles only).
void check_msh_header(const std::filesystem::path& file, const MeshSource& source);

}  // namespace rockdd

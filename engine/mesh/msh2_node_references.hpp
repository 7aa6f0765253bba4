#pragma once
// Elements of an ASCII format-2 .msh that name nodes the file does not define.
#include <filesystem>

#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// Throws InputError (through `source`) when an element of the ASCII format-2 .msh `file`
/// names a node tag that is not among the nodes its $Nodes section declares (the count on the
/// line after $Nodes, then that many node lines). Other defects are left to Gmsh, which
/// reports them; files of other formats are not read. Call after check_msh_header.
void check_msh2_node_references(const std::filesystem::path& file, const MeshSource& source);

}  // namespace rockdd

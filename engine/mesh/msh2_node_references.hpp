#pragma once
// What an ASCII format-2 .msh must not hold for Gmsh 4.8 to read it safely.
#include <filesystem>

#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// Throws InputError (through `source`) when the ASCII format-2 .msh `file` has what Gmsh 4.8's
/// reader crashes on: an element naming a node tag that its $Nodes section does not declare
/// (the count after $Nodes, then that many nodes), partition or parent tags, a second $Nodes
/// or $Elements section or format-1 sections, or counts, nodes and elements that cannot be read
/// as Gmsh reads them (fscanf, across line breaks). Other defects are left to Gmsh, which
/// reports them; files of other formats are not read. Call after check_msh_header.
void check_msh2_node_references(const std::filesystem::path& file, const MeshSource& source);

}  // namespace rockdd

#pragma once
// What a format-4.1 .msh must hold before Gmsh 4.8 is given it.
#include <filesystem>

#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// Throws InputError (through `source`), naming the file and line (ASCII) or byte (binary)
/// and what was expected, unless the format-4.1 `file` (ASCII or binary) holds:
/// - only the sections $MeshFormat, $PhysicalNames, $Entities, $Nodes and $Elements, each at
///   most once, $Nodes and $Elements present, $Entities before $Nodes before $Elements;
/// - in $Entities, its four counts and that many points, curves, surfaces and volumes with
///   positive tags, each once, physical tags >= 1 and bounding entities that exist;
/// - in $Nodes and $Elements, headers whose counts equal what their blocks hold, blocks on
///   entities of $Entities (dimension 0-3, tag >= 1), element types 1-31 of the block's
///   dimension, tags within the header's [min, max], each once, and elements whose nodes are
///   nodes of $Nodes;
/// - node and element counts whose run fits the memory budget (mesh_budget).
/// Files of other versions are not read (check_msh_header admits 2.x and 4.1 only).
void check_msh4_contents(const std::filesystem::path& file, const MeshSource& source);

}  // namespace rockdd

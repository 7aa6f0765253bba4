#pragma once
// The mesh spec of a mesh file, for the mesh tests (only the mesh library behind them).
#include <filesystem>

#include "engine/mesh/mesh.hpp"

namespace rockdd::test {

/// The mesh spec of a .geo or .msh file at `path`.
inline MeshSpec mesh_file(MeshSpec::Kind kind, const std::filesystem::path& path) {
  MeshSpec spec;
  spec.kind = kind;
  spec.file = path;
  return spec;
}

}  // namespace rockdd::test

#pragma once
// The Gmsh module: Gmsh and the ~90 libraries it links take 0.14 s to load, in every process
// that links them, so the mesher lives in a module (librockdd_gmsh.so) that build_mesh opens
// on first use. A run whose mesh comes from the mesh cache never loads Gmsh.
#include <filesystem>
#include <string>

#include "engine/mesh/mesh.hpp"

namespace rockdd {

/// What the module gives the engine (one table, so that one symbol is looked up).
struct GmshModuleEntry {
  int abi = 0;  // kGmshModuleAbi of the module's build; another value is refused
  Mesh (*mesh)(const MeshSpec& spec, const std::filesystem::path& scene_file, int gmsh_threads);
  std::string (*version)();  // Gmsh's General.Version, as the loaded library reports it
};

/// Bumped whenever GmshModuleEntry or the types it passes change shape.
inline constexpr int kGmshModuleAbi = 1;

/// The module's side, in gmsh_mesher.cpp: meshes with Gmsh (what build_mesh documents).
Mesh mesh_with_gmsh(const MeshSpec& spec, const std::filesystem::path& scene_file,
                    int gmsh_threads);

/// The engine's side: the module, opened once per process. Throws std::runtime_error naming
/// the places it looked when it cannot be opened.
const GmshModuleEntry& gmsh_module();

/// build_mesh without its meshing process: Gmsh runs in this process, without limits, and a
/// crash in Gmsh is this process's. For the fuzz harnesses, which must see Gmsh's crashes.
Mesh build_mesh_in_this_process(const MeshSpec& spec, const std::filesystem::path& scene_file,
                                int gmsh_threads = 1);

/// Identifies the Gmsh library that the module would load without loading it: its resolved
/// file name (with the full version), size and modification time; for the mesh cache's key.
/// Empty when the file cannot be found (the caller then asks the module for its version).
std::string gmsh_library_identity();

}  // namespace rockdd

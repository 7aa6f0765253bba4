#pragma once
// Meshes kept between runs: a run of an unchanged geometry, size and mesher skips Gmsh.
// An entry is one file named by a hash of everything the mesh depends on; it holds that
// description in full (so a hash collision is a miss, never a wrong mesh) and a checksum.
#include <filesystem>
#include <optional>
#include <string>

#include "engine/mesh/mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Where a run's mesh came from.
enum class MeshCacheOutcome {
  off,          // no cache folder: meshed
  hit,          // read from the cache
  miss,         // meshed, then stored
  uncacheable,  // meshed: a .geo that reads other files, or a file that could not be read
};

/// A mesh and where it came from.
struct CachedMesh {
  Mesh mesh;
  MeshCacheOutcome cache = MeshCacheOutcome::off;
};

/// build_mesh, through the cache in `cache_dir` (nullopt: no cache). A hit is bitwise the
/// mesh build_mesh made for the same key. Throws InputError as build_mesh does.
CachedMesh build_mesh_with_cache(const MeshSpec& spec, const std::filesystem::path& scene_file,
                                 const std::optional<std::filesystem::path>& cache_dir);

/// "off", "hit", "miss" or "uncacheable", as summary.json reports it.
const char* mesh_cache_outcome_name(MeshCacheOutcome outcome);

/// The cache folder: $ROCKDD_MESH_CACHE if set ("off" or empty: no cache), else
/// $XDG_CACHE_HOME/rockdd/meshes, else $HOME/.cache/rockdd/meshes; nullopt when off or when
/// none of these is set.
std::optional<std::filesystem::path> mesh_cache_dir();

/// What a mesh of `spec` depends on, as text: the mesher's version, the code that meshes and
/// orders, every field of `spec` (exact bits), and a hash of the bytes of its .geo or .msh.
/// nullopt for a .geo that reads other files (Include, Merge, ShapeFromFile, ...), whose
/// content this cannot see, and for files that cannot be read.
std::optional<std::string> mesh_cache_key(const MeshSpec& spec);

/// The mesh stored under `key` in `dir`, or nullopt when there is none, or it was written for
/// another key, or it is damaged (short, bad checksum): a miss, never an error.
std::optional<Mesh> read_cached_mesh(const std::filesystem::path& dir, const std::string& key);

/// Stores `mesh` under `key` in `dir` (created if missing), atomically, so that concurrent
/// runs and a killed one leave either a whole entry or none. Failures are ignored: a cache
/// that cannot be written costs a remesh next time, not the run.
void write_cached_mesh(const std::filesystem::path& dir, const std::string& key, const Mesh& mesh);

}  // namespace rockdd

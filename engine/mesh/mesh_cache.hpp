#pragma once
// Meshes kept between runs: a run of an unchanged geometry, size and mesher skips Gmsh.
// An entry is one file named by a hash of everything the mesh depends on; it holds that
// description in full (so a hash collision is a miss, never a wrong mesh) and a checksum.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

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

/// Where a mesh is kept in the cache: the folder and the mesh's key. What is computed from the
/// mesh and kept too (the fill-reducing ordering of its system) is stored next to it, under
/// this key plus its own.
struct MeshCacheSlot {
  std::filesystem::path dir;
  std::string key;
};

/// A mesh and where it came from.
struct CachedMesh {
  Mesh mesh;
  MeshCacheOutcome cache = MeshCacheOutcome::off;
  std::optional<MeshCacheSlot> slot;  // set on a hit or a miss
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

/// A fill-reducing ordering kept next to a cached mesh: the elimination order of the
/// equations (perm[k]: the equation eliminated k-th) and the name of the method that made it.
struct CachedOrdering {
  std::vector<std::int32_t> perm;
  std::string method;
};

/// The ordering stored for the mesh of `slot`, the ordering described by `ordering_key`
/// (strategy, library versions, code) and exactly this symmetric pattern (its upper triangle
/// as compressed columns, which the entry holds in full); nullopt when there is none, or it
/// was written for another mesh, key or pattern, or it is damaged (short, bad checksum, not a
/// permutation): a miss, never an error and never another pattern's ordering.
std::optional<CachedOrdering> read_cached_ordering(const MeshCacheSlot& slot,
                                                   const std::string& ordering_key,
                                                   std::span<const std::int32_t> col_ptr,
                                                   std::span<const std::int32_t> row_idx);

/// Stores `ordering` for that mesh, key and pattern, atomically; failures are ignored, as
/// write_cached_mesh's are.
void write_cached_ordering(const MeshCacheSlot& slot, const std::string& ordering_key,
                           std::span<const std::int32_t> col_ptr,
                           std::span<const std::int32_t> row_idx, const CachedOrdering& ordering);

/// The file of the ordering entry read_cached_ordering() looks for (for tests).
std::filesystem::path cached_ordering_path(const MeshCacheSlot& slot,
                                           const std::string& ordering_key,
                                           std::span<const std::int32_t> col_ptr,
                                           std::span<const std::int32_t> row_idx);

}  // namespace rockdd

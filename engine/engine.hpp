#pragma once
// rockdd's public API: what the command line, the tests and other tools call.
//
//   rockdd::Scene scene = rockdd::load_scene("data/brazilian_disk_elastic.toml");
//   rockdd::Simulation sim(scene, rockdd::build_scene_model(scene));
//   rockdd::RunResult result = sim.run({.out_root = "out", .threads = 2});
#include <filesystem>
#include <string>
#include <vector>

#include "engine/common/errors.hpp"
#include "engine/model/model.hpp"
#include "engine/report/setup_report.hpp"
#include "engine/scene/scene.hpp"
#include "engine/simulation.hpp"

namespace rockdd {

/// Reads and validates a scene file (with `--set key.path=value` overrides) and checks that
/// every feature it uses is available. Throws InputError.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

/// Meshes the scene through Gmsh, or takes its mesh from the mesh cache (mesh_cache_dir():
/// $ROCKDD_MESH_CACHE, off with "off"), and builds its model (blocks, materials, named sets).
Model build_scene_model(const Scene& scene);

/// A model, and what making it took.
struct BuiltModel {
  Model model;
  SetupReport setup;  // meshing, model and the mesh cache's outcome (scene and startup: unset)
  /// Where the mesh is kept in the mesh cache (none when the cache is off or cannot hold it):
  /// pass it to the Simulation, which keeps its fill-reducing ordering there too.
  std::optional<MeshCacheSlot> mesh_slot;
};

/// build_scene_model, timed: pass `setup` on in RunOptions for a summary that accounts for it.
BuiltModel build_scene_model_reported(const Scene& scene);

/// The rockdd version string.
const char* version();

}  // namespace rockdd

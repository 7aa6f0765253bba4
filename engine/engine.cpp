#include <utility>

#include "engine/common/timers.hpp"
#include "engine/engine.hpp"
#include "engine/mesh/mesh_cache.hpp"
#include "engine/model/element_strength.hpp"
#include "engine/scene/scene_reader.hpp"

namespace rockdd {

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return read_scene(file, overrides);
}

BuiltModel build_scene_model_reported(const Scene& scene) {
  BuiltModel built;
  CachedMesh mesh;
  {
    ScopedTimer timer(built.setup.meshing);
    mesh = build_mesh_with_cache(scene.mesh, scene.file, mesh_cache_dir());
  }
  built.setup.mesh_cache = mesh.cache;
  built.mesh_slot = std::move(mesh.slot);
  ScopedTimer timer(built.setup.model);
  built.model = build_model(scene, std::move(mesh.mesh));
  assign_element_strengths(scene, built.model);
  return built;
}

Model build_scene_model(const Scene& scene) {
  return build_scene_model_reported(scene).model;
}

const char* version() {
  return ROCKDD_VERSION;
}

}  // namespace rockdd

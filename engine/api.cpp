#include "engine/mesh/mesh.hpp"
#include "engine/model/element_strength.hpp"
#include "engine/rockdd.hpp"
#include "engine/scene/scene_reader.hpp"
#include "engine/supported_features.hpp"

namespace rockdd {

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  Scene scene = read_scene(file, overrides);
  check_supported_features(scene);
  return scene;
}

Model build_scene_model(const Scene& scene) {
  Model model = build_model(scene, build_mesh(scene.mesh, scene.file));
  assign_element_strengths(scene, model);
  return model;
}

const char* version() {
  return ROCKDD_VERSION;
}

}  // namespace rockdd

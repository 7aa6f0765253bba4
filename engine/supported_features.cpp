#include "engine/supported_features.hpp"

#include <string>

#include "engine/errors.hpp"

namespace rockdd {

void check_supported_features(const Scene& scene) {
  const std::string file = scene.file.string();
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const JointSpec& joint = scene.joints[i];
    const std::string key = "joint[" + std::to_string(i) + "].";
    // Fracture faces come with the damage stage.
    if (joint.between.size() == 1 && joint.between[0] == "crack")
      throw InputError(file, key + "between",
                       "joints on fracture faces (\"crack\") are not supported yet");
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialSpec& m = scene.materials[i];
    const std::string key = "material[" + std::to_string(i) + "].";
    if (m.tensile_strength)
      throw InputError(file, key + "tensile_strength", "damage and fracture are not supported yet");
    if (m.cohesion)
      throw InputError(file, key + "cohesion", "damage and fracture are not supported yet");
    if (m.compressive_strength)
      throw InputError(file, key + "compressive_strength",
                       "damage and fracture are not supported yet");
    if (m.homogeneity)
      throw InputError(file, key + "homogeneity", "Weibull heterogeneity is not supported yet");
  }
}

}  // namespace rockdd

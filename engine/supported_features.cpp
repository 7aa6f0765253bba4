#include "engine/supported_features.hpp"

#include <string>

#include "engine/errors.hpp"

namespace rockdd {

void check_supported_features(const Scene& scene) {
  const std::string file = scene.file.string();
  // The contact stage (engine/contact) runs, but the sliding block still lags the analytic
  // solution by ~5 % at 1.5 s; it stays off until it meets the 1 % of its issue.
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const JointSpec& joint = scene.joints[i];
    const std::string key = "joint[" + std::to_string(i) + "].";
    // Frictionless contact is validated (the sliding block); friction, cohesion and tension
    // on joints, and fracture faces, come with the rest of the contact and damage stages.
    if (joint.between.size() == 1 && joint.between[0] == "crack")
      throw InputError(file, key + "between",
                       "joints on fracture faces (\"crack\") are not supported yet");
    if (joint.friction_angle != 0.0)
      throw InputError(file, key + "friction_angle",
                       "friction on joints is not supported yet (use 0)");
    if (joint.cohesion != 0.0)
      throw InputError(file, key + "cohesion", "cohesion on joints is not supported yet (use 0)");
    if (joint.tensile_strength != 0.0)
      throw InputError(file, key + "tensile_strength",
                       "tensile strength on joints is not supported yet (use 0)");
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

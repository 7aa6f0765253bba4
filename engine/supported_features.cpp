#include "engine/supported_features.hpp"

#include <string>

#include "engine/errors.hpp"

namespace rockdd {

void check_supported_features(const Scene& scene) {
  const std::string file = scene.file.string();
  // The contact stage (engine/contact) runs, but the sliding block still lags the analytic
  // solution by ~5 % at 1.5 s; it stays off until it meets the 1 % of its issue.
  if (!scene.joints.empty())
    throw InputError(file, "joint", "contact between blocks ([[joint]]) is not supported yet");
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

#include "engine/damage/first_damage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rockdd {

FirstDamage locate_first_damage(const Model& model, long step, double time) {
  FirstDamage first{step, time, 0, 0.0, 0.0, 0.0};
  std::vector<std::array<double, 2>> centroids;
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    if (model.damage[e] > 0.0) centroids.push_back(reference_centroid(model, e));
  first.elements = static_cast<std::int32_t>(centroids.size());
  for (const auto& c : centroids) {
    first.x += c[0] / first.elements;
    first.y += c[1] / first.elements;
  }
  for (const auto& c : centroids)
    first.spread = std::max(first.spread, std::hypot(c[0] - first.x, c[1] - first.y));
  return first;
}

}  // namespace rockdd

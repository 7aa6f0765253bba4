#include "engine/damage/disintegration.hpp"

#include <algorithm>
#include <vector>

namespace rockdd {

BlockSpread fracturing_block_spread(const Model& model) {
  std::vector<double> area;
  double total = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (!model.materials[model.element_material[e]].has_damage()) continue;
    const auto block = static_cast<std::size_t>(model.element_block[e]);
    if (block >= area.size()) area.resize(block + 1, 0.0);
    area[block] += model.area0[e];
    total += model.area0[e];
  }
  BlockSpread spread;
  if (total <= 0.0) return spread;
  spread.blocks = static_cast<std::int32_t>(
      std::count_if(area.begin(), area.end(), [](double a) { return a > 0.0; }));
  spread.largest_share = *std::max_element(area.begin(), area.end()) / total;
  return spread;
}

const char* disintegration_cause_name(DisintegrationCause cause) {
  return cause == DisintegrationCause::fragments ? "fragments" : "no_load_path";
}

}  // namespace rockdd

#include "engine/damage/separation.hpp"

#include <algorithm>
#include <functional>

namespace rockdd {

SeparationWatch::SeparationWatch(const Model& model, double share)
    : sides_(build_edge_adjacency(model.conn, "separation")),
      rock_(static_cast<std::size_t>(model.num_elements())) {
  double rock_area = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    rock_[e] = model.materials[model.element_material[e]].has_damage() ? 1 : 0;
    if (rock_[e]) rock_area += model.area0[e];
  }
  least_area_ = share * rock_area;
  // Counted on the intact mesh: joints and blocks the scene starts with are not a separation.
  const std::vector<double> intact(model.damage.size(), 0.0);
  parts_at_start_ = large_parts(model, intact).size();
}

std::vector<double> SeparationWatch::separated_parts(const Model& model) const {
  std::vector<double> parts = large_parts(model, model.damage);
  if (parts.size() <= parts_at_start_) parts.clear();
  return parts;
}

std::vector<double> SeparationWatch::large_parts(const Model& model,
                                                 std::span<const double> damage) const {
  const std::int32_t num_elements = model.num_elements();
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(num_elements), 0);
  std::vector<std::int32_t> stack;
  std::vector<double> parts;
  for (std::int32_t seed = 0; seed < num_elements; ++seed) {
    if (seen[seed] || !rock_[seed] || damage[seed] > 0.0) continue;
    double area = 0.0;
    seen[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::int32_t e = stack.back();
      stack.pop_back();
      area += model.area0[e];
      for (int k = 0; k < 3; ++k) {
        const std::int32_t n = sides_.neighbor[3 * e + k];
        if (n < 0 || seen[n] || !rock_[n] || damage[n] > 0.0) continue;
        seen[n] = 1;
        stack.push_back(n);
      }
    }
    if (area >= least_area_) parts.push_back(area);
  }
  std::sort(parts.begin(), parts.end(), std::greater<>());
  return parts;
}

}  // namespace rockdd

#include "engine/damage/fragment_anchors.hpp"

#include <algorithm>
#include <numeric>

namespace rockdd {

std::vector<AnchorSpring> anchor_fragments(const Model& model, double relative, double absolute) {
  const std::int32_t num_elements = model.num_elements();
  std::vector<std::int32_t> elements_in_block(static_cast<std::size_t>(model.num_blocks), 0);
  for (std::int32_t e = 0; e < num_elements; ++e) ++elements_in_block[model.element_block[e]];

  // The copies of each root node, grouped: nodes sorted by (root, id).
  const std::int32_t num_nodes = model.num_nodes();
  std::vector<std::int32_t> by_root(static_cast<std::size_t>(num_nodes));
  std::iota(by_root.begin(), by_root.end(), 0);
  std::sort(by_root.begin(), by_root.end(), [&](std::int32_t a, std::int32_t b) {
    return model.node_root[a] != model.node_root[b] ? model.node_root[a] < model.node_root[b]
                                                    : a < b;
  });
  std::vector<std::int32_t> first_copy(static_cast<std::size_t>(num_nodes));  // index in by_root
  for (std::int32_t i = 0; i < num_nodes; ++i)
    first_copy[by_root[i]] = i > 0 && model.node_root[by_root[i]] == model.node_root[by_root[i - 1]]
                                 ? first_copy[by_root[i - 1]]
                                 : i;
  auto for_each_copy = [&](std::int32_t node, auto&& visit) {
    const std::int32_t root = model.node_root[node];
    for (std::int32_t i = first_copy[node]; i < num_nodes && model.node_root[by_root[i]] == root;
         ++i)
      if (by_root[i] != node) visit(by_root[i]);
  };

  std::vector<AnchorSpring> springs;
  for (std::int32_t e = 0; e < num_elements; ++e) {
    const std::int32_t block = model.element_block[e];
    if (elements_in_block[block] != 1) continue;
    const std::int32_t* corner = &model.conn[3 * static_cast<std::size_t>(e)];
    // Candidate partner blocks, scored by (more than one element, corners they hold).
    std::int32_t best = -1, best_corners = 0;
    bool best_large = false;
    for (int k = 0; k < 3; ++k)
      for_each_copy(corner[k], [&](std::int32_t copy) {
        const std::int32_t candidate = model.node_block[copy];
        if (candidate == block) return;
        std::int32_t corners = 0;
        for (int j = 0; j < 3; ++j)
          for_each_copy(corner[j], [&](std::int32_t other) {
            if (model.node_block[other] == candidate) ++corners;
          });
        const bool large = elements_in_block[candidate] > 1;
        if (best < 0 || large > best_large || (large == best_large && corners > best_corners) ||
            (large == best_large && corners == best_corners && candidate < best)) {
          best = candidate;
          best_corners = corners;
          best_large = large;
        }
      });
    const double young_t = model.young[e] * model.thickness;
    for (int k = 0; k < 3; ++k) {
      std::int32_t partner = -1;
      if (best >= 0)
        for_each_copy(corner[k], [&](std::int32_t copy) {
          if (model.node_block[copy] == best && (partner < 0 || copy < partner)) partner = copy;
        });
      springs.push_back({corner[k], partner, (partner >= 0 ? relative : absolute) * young_t});
    }
  }
  return springs;
}

}  // namespace rockdd

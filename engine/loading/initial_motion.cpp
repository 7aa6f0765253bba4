#include "engine/loading/initial_motion.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/common/errors.hpp"

namespace rockdd {

void apply_initial_motion(const Scene& scene, Model& model) {
  for (const InitialSpec& init : scene.initial) {
    const auto& bodies = model.sets.bodies;
    const auto body = std::find(bodies.begin(), bodies.end(), init.body) - bodies.begin();
    double cx = 0, cy = 0, m = 0;
    std::vector<std::uint8_t> in(static_cast<std::size_t>(model.num_nodes()), 0);
    for (std::int32_t e = 0; e < model.num_elements(); ++e)
      if (model.element_body[e] == body)
        for (int k = 0; k < 3; ++k) in[model.conn[3 * e + k]] = 1;
    for (std::int32_t n = 0; n < model.num_nodes(); ++n)
      if (in[n]) {
        cx += model.node_mass[n] * model.X[2 * n];
        cy += model.node_mass[n] * model.X[2 * n + 1];
        m += model.node_mass[n];
      }
    if (m <= 0)
      throw InputError(scene.file.string(), "initial.body", "no body named '" + init.body + "'");
    cx /= m;
    cy /= m;
    for (std::int32_t n = 0; n < model.num_nodes(); ++n)
      if (in[n]) {
        model.v[2 * n] = init.velocity[0] - init.angular_velocity * (model.X[2 * n + 1] - cy);
        model.v[2 * n + 1] = init.velocity[1] + init.angular_velocity * (model.X[2 * n] - cx);
      }
  }
}

}  // namespace rockdd

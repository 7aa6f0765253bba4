#include "engine/damage/fragment_restraint.hpp"

#include <algorithm>

namespace rockdd {

FragmentRestraint::FragmentRestraint(const Model& model, const BoundaryConditions& bc,
                                     double fraction) {
  const std::vector<std::uint8_t> free = unrestrained_blocks(model, bc);
  std::vector<double> k(static_cast<std::size_t>(model.num_nodes()), 0.0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (!free[model.element_block[e]]) continue;
    // Like a lumped mass: each corner takes a third of the element's share.
    const double share = fraction * model.young[e] * model.thickness / 3.0;
    for (int c = 0; c < 3; ++c) k[model.conn[3 * static_cast<std::size_t>(e) + c]] += share;
  }
  for (std::int32_t n = 0; n < model.num_nodes(); ++n)
    if (k[n] > 0.0) {
      nodes_.push_back(n);
      stiffness_.push_back(k[n]);
    }
}

void FragmentRestraint::add_stiffness(std::span<const std::int32_t> equation,
                                      std::span<const std::int32_t> diagonal,
                                      std::span<double> values) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    for (int c = 0; c < 2; ++c) {
      const std::int32_t eq = equation[2 * static_cast<std::size_t>(nodes_[i]) + c];
      if (eq >= 0) values[diagonal[eq]] += stiffness_[i];
    }
}

void FragmentRestraint::forces(std::span<const double> du, std::span<double> force) const {
  std::fill(force.begin(), force.end(), 0.0);
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    for (int c = 0; c < 2; ++c) {
      const std::size_t d = 2 * static_cast<std::size_t>(nodes_[i]) + c;
      force[d] = stiffness_[i] * du[d];
    }
}

double FragmentRestraint::energy(std::span<const double> du) const {
  double energy = 0.0;
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    for (int c = 0; c < 2; ++c) {
      const double x = du[2 * static_cast<std::size_t>(nodes_[i]) + c];
      energy += 0.5 * stiffness_[i] * x * x;
    }
  return energy;
}

}  // namespace rockdd

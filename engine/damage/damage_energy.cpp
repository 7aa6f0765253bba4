#include "engine/damage/damage_energy.hpp"

#include <cstddef>
#include <cstdint>

#include "kernels/damage_law.hpp"

namespace rockdd {

double released_by_damage(const Model& model, std::span<const double> damage_before,
                          std::span<const double> strain) {
  // At `strain`, where the modulus drops; the deformation the softer element takes on
  // afterwards is stored at the new modulus (counted in the strain energy).
  double energy = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    if (model.damage[e] > damage_before[e])
      energy += kernels::damage_dissipation(
                    &strain[3 * static_cast<std::size_t>(e)], model.young[e], model.poisson[e],
                    model.plane, damage_before[e], model.damage[e], kernels::kStiffnessFloor) *
                model.area0[e];
  return energy * model.thickness;
}

}  // namespace rockdd

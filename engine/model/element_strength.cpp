#include "engine/model/element_strength.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "kernels/damage_law.hpp"
#include "kernels/weibull.hpp"

namespace rockdd {
namespace {

bool drawn(const MaterialSpec& m, const std::string& name) {
  if (!m.homogeneity) return false;
  for (const std::string& h : m.heterogeneous)
    if (h == name) return true;
  return false;
}

}  // namespace

void assign_element_strengths(const Scene& scene, Model& model) {
  const auto num_elements = static_cast<std::size_t>(model.num_elements());
  bool any_damage = false;
  for (const MaterialSpec& m : scene.materials) any_damage = any_damage || m.has_damage();
  if (!any_damage) return;  // elastic scenes carry no strength arrays at all
  model.tensile_strength.assign(num_elements, 0.0);
  model.compressive_strength.assign(num_elements, 0.0);
  model.friction_angle.assign(num_elements, 0.0);

  // Reference area for weakest-link scaling: the mean element area of each material.
  std::vector<double> mean_area(scene.materials.size(), 0.0);
  std::vector<double> count(scene.materials.size(), 0.0);
  for (std::size_t e = 0; e < num_elements; ++e) {
    mean_area[static_cast<std::size_t>(model.element_material[e])] += std::abs(model.area0[e]);
    count[static_cast<std::size_t>(model.element_material[e])] += 1.0;
  }
  for (std::size_t i = 0; i < mean_area.size(); ++i)
    if (count[i] > 0) mean_area[i] /= count[i];

  for (std::size_t e = 0; e < num_elements; ++e) {
    const auto mi = static_cast<std::size_t>(model.element_material[e]);
    const MaterialSpec& m = scene.materials[mi];
    auto value = [&](const std::string& name, double mean, DrawnParameter key) {
      return drawn(m, name) ? kernels::weibull_draw(mean, *m.homogeneity, m.seed, e,
                                                    static_cast<std::uint64_t>(key))
                            : mean;
    };
    model.young[e] = value("young", m.young, DrawnParameter::young);
    if (!m.has_damage()) continue;
    // Weakest link: a larger element holds more flaws (strength ~ (A_ref / A)^(1/m)).
    const double size_factor =
        m.weibull_size_scaling && m.homogeneity
            ? std::pow(mean_area[mi] / std::abs(model.area0[e]), 1.0 / *m.homogeneity)
            : 1.0;
    const double phi = m.friction_angle.value_or(0.0) * std::numbers::pi / 180.0;
    model.friction_angle[e] = phi;
    if (m.tensile_strength)
      model.tensile_strength[e] = size_factor * value("tensile_strength", *m.tensile_strength,
                                                      DrawnParameter::tensile_strength);
    if (m.cohesion)
      model.compressive_strength[e] =
          size_factor * kernels::compressive_strength(
                            value("cohesion", *m.cohesion, DrawnParameter::cohesion), phi);
    else if (m.compressive_strength)
      model.compressive_strength[e] =
          size_factor *
          value("compressive_strength", *m.compressive_strength, DrawnParameter::cohesion);
  }
}

}  // namespace rockdd

#pragma once
// Per-element strengths of damageable materials, with the Weibull heterogeneity of paper
// eq. (1): each listed parameter of each element is drawn with the scene's mean and
// homogeneity index m, from a counter-based generator keyed by (seed, element, parameter),
// so the same seed gives the same specimen whatever the threads (METHOD.md "Heterogeneity").
#include <cstdint>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Parameter keys of the generator: fixed, so a specimen does not change when another
/// parameter is added to `heterogeneous`.
enum class DrawnParameter : std::uint64_t { young = 0, tensile_strength = 1, cohesion = 2 };

/// Draws the heterogeneous parameters of every element (model.young and the strengths),
/// with optional weakest-link size scaling of strengths, and fills model.tensile_strength,
/// model.compressive_strength (fc0, from cohesion and friction angle when given so) and
/// model.friction_angle for elements of damageable materials (0 where a law is off).
void assign_element_strengths(const Scene& scene, Model& model);

}  // namespace rockdd

#pragma once
// The elastic energy a damage pass releases: what the energy balance books as damage.
#include <span>

#include "engine/model/model.hpp"

namespace rockdd {

/// Energy (J) released where model.damage grew past `damage_before` at `strain` (3 per
/// element): each element's 1/2 eps.D eps times its modulus drop (kernels::damage_dissipation)
/// and its volume. Summed serially in element order: the total does not depend on threads.
double released_by_damage(const Model& model, std::span<const double> damage_before,
                          std::span<const double> strain);

}  // namespace rockdd

#pragma once
// Stress recovery and the nodal internal force it implies, f_int = sum t A B^T sigma.
#include <span>

#include "engine/assembly/element_coloring.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// For displacement `u`: fills each element's `strain` and `stress` (3 per element) and the
/// nodal internal force `f_int` (2 per node). Deterministic for any thread count.
void compute_internal_force(const Model& model, const ElementColoring& coloring,
                            std::span<const double> u, std::span<double> strain,
                            std::span<double> stress, std::span<double> f_int);

/// Strain energy, sum of 1/2 sigma : eps t A over the elements (J).
double strain_energy(const Model& model, std::span<const double> strain,
                     std::span<const double> stress);

}  // namespace rockdd

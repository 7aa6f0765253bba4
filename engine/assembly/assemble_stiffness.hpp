#pragma once
// Numeric side of assembly: element stiffness into the fixed pattern, in parallel.
#include <span>

#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// K_eff = sum of element stiffness (damaged moduli, reference geometry turned by each
/// element's frame rotation, Model::rotation) plus
/// `mass_coefficient` times the lumped mass on the diagonal (2/dt^2 for DDA inertia).
/// Fills `values` (pattern order); bitwise identical for any thread count.
void assemble_stiffness(const Model& model, const ElementColoring& coloring,
                        const StiffnessLayout& layout, std::span<const std::int32_t> equation,
                        double mass_coefficient, std::span<double> values);

}  // namespace rockdd

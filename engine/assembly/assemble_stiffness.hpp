#pragma once
// Numeric side of assembly: element stiffness into the fixed pattern, in parallel.
#include <cstddef>
#include <span>

#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/element_state.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/model/model.hpp"
#include "kernels/corotation.hpp"
#include "kernels/cst.hpp"

namespace rockdd {

/// Element e's stiffness with Young's modulus `young` (its own Poisson ratio, the model's
/// plane kind and thickness), reference geometry turned into the element's frame
/// (Model::rotation): what assemble_stiffness adds for it at its damaged modulus.
inline void element_stiffness(const Model& model, std::int32_t e, double young, double k[36]) {
  double xy[6], d[9];
  gather_element(model.conn, e, model.X, xy);
  kernels::elasticity_matrix(young, model.poisson[e], plane_kind(model.plane), d);
  kernels::cst_stiffness(xy, d, model.thickness, k);
  if (!model.rotation.empty() && model.rotation[e] != 0.0)
    kernels::rotate_element_matrix(kernels::Rotation(model.rotation[e]), k);
}

/// values += k at element e's entries of the layout (upper triangle; rows and columns of
/// prescribed dofs dropped).
inline void scatter_element_matrix(const StiffnessLayout& layout, std::int32_t e,
                                   const double k[36], std::span<double> values) {
  const std::int32_t* to = &layout.scatter[static_cast<std::size_t>(e) * kElementUpperEntries];
  for (int a = 0; a < 6; ++a)
    for (int b = a; b < 6; ++b, ++to)
      if (*to >= 0) values[static_cast<std::size_t>(*to)] += k[6 * a + b];
}

/// K_eff = sum of element stiffness (damaged moduli, reference geometry turned by each
/// element's frame rotation, Model::rotation) plus
/// `mass_coefficient` times the lumped mass on the diagonal (2/dt^2 for DDA inertia).
/// Fills `values` (pattern order); bitwise identical for any thread count.
void assemble_stiffness(const Model& model, const ElementColoring& coloring,
                        const StiffnessLayout& layout, std::span<const std::int32_t> equation,
                        double mass_coefficient, std::span<double> values);

}  // namespace rockdd

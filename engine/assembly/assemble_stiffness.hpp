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

/// The upper triangle (kernels::cst_isotropic_stiffness_upper's order) of element e's stiffness
/// with Young's modulus `young` (its own Poisson ratio, the model's plane kind and
/// thickness), reference geometry turned into the element's frame (Model::rotation): what
/// assemble_stiffness adds for it at its damaged modulus.
inline void element_stiffness(const Model& model, std::int32_t e, double young,
                              double ku[kElementUpperEntries]) {
  double xy[6];
  gather_element(model.conn, e, model.X, xy);
  const kernels::IsotropicModuli d =
      kernels::isotropic_moduli(young, model.poisson[e], model.plane);
  kernels::cst_isotropic_stiffness_upper(xy, d, model.thickness, ku);
  if (model.rotation.empty() || model.rotation[e] == 0.0) return;
  double k[36];
  for (int a = 0, i = 0; a < 6; ++a)
    for (int b = a; b < 6; ++b, ++i) k[6 * a + b] = k[6 * b + a] = ku[i];
  kernels::rotate_element_matrix(kernels::Rotation(model.rotation[e]), k);
  for (int a = 0, i = 0; a < 6; ++a)
    for (int b = a; b < 6; ++b, ++i) ku[i] = k[6 * a + b];
}

/// values += ku (an upper triangle, element_stiffness's order) at element e's entries of the
/// layout; rows and columns of prescribed dofs dropped.
inline void scatter_element_matrix(const StiffnessLayout& layout, std::int32_t e,
                                   const double ku[kElementUpperEntries],
                                   std::span<double> values) {
  const std::int32_t* to = &layout.scatter[static_cast<std::size_t>(e) * kElementUpperEntries];
  for (int i = 0; i < kElementUpperEntries; ++i)
    if (to[i] >= 0) values[static_cast<std::size_t>(to[i])] += ku[i];
}

/// K_eff = sum of element stiffness (damaged moduli, reference geometry turned by each
/// element's frame rotation, Model::rotation) plus
/// `mass_coefficient` times the lumped mass on the diagonal (2/dt^2 for DDA inertia).
/// Fills `values` (pattern order); bitwise identical for any thread count.
void assemble_stiffness(const Model& model, const ElementColoring& coloring,
                        const StiffnessLayout& layout, std::span<const std::int32_t> equation,
                        double mass_coefficient, std::span<double> values);

}  // namespace rockdd

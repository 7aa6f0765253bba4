#include "engine/assembly/modulus_change.hpp"

#include <array>
#include <cmath>

#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_state.hpp"
#include "kernels/corotation.hpp"

namespace rockdd {

void changed_elements(const Model& model, std::span<const double> damage_before,
                      std::vector<std::int32_t>& changed) {
  changed.clear();
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    if (model.damage[e] != damage_before[e]) changed.push_back(e);
}

void modulus_change_terms(const Model& model, std::span<const std::int32_t> equation,
                          std::span<const std::int32_t> changed,
                          std::span<const double> damage_before, LowRankTerms& added,
                          LowRankTerms& removed) {
  added.clear();
  removed.clear();
  const kernels::PlaneKind plane = model.plane;
  for (const std::int32_t e : changed) {
    // The same moduli assemble_stiffness uses, so the terms are its difference exactly.
    const double before = kernels::damaged_modulus(model.young[e], damage_before[e]);
    const double after = kernels::damaged_modulus(model.young[e], model.damage[e]);
    if (after == before) continue;  // both at the floor
    double xy[6], d[9], w[18];
    gather_element(model.conn, e, model.X, xy);
    kernels::elasticity_matrix(std::abs(after - before), model.poisson[e], plane, d);
    kernels::cst_stiffness_factor(xy, d, model.thickness, w);
    std::array<std::int32_t, 6> rows;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = model.conn[3 * e + k];
      rows[2 * k] = equation[2 * n];
      rows[2 * k + 1] = equation[2 * n + 1];
    }
    const bool turned = !model.rotation.empty() && model.rotation[e] != 0.0;
    const kernels::Rotation turn(turned ? model.rotation[e] : 0.0);
    LowRankTerms& terms = after > before ? added : removed;
    for (int j = 0; j < 3; ++j) {
      double column[6];
      for (int a = 0; a < 6; ++a) column[a] = w[3 * a + j];
      if (turned) kernels::rotate_nodal(turn, column);
      terms.add_column(rows, column);
    }
  }
}

void add_modulus_change(const Model& model, const StiffnessLayout& layout,
                        std::span<const std::int32_t> changed,
                        std::span<const double> damage_before, std::span<double> values) {
  for (const std::int32_t e : changed) {
    const double before = kernels::damaged_modulus(model.young[e], damage_before[e]);
    const double after = kernels::damaged_modulus(model.young[e], model.damage[e]);
    if (after == before) continue;
    double ku[kElementUpperEntries];
    element_stiffness(model, e, after - before, ku);
    scatter_element_matrix(layout, e, ku, values);
  }
}

}  // namespace rockdd

#include "engine/assembly/assemble_stiffness.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "engine/assembly/element_state.hpp"
#include "kernels/corotation.hpp"

namespace rockdd {

void assemble_stiffness(const Model& model, const ElementColoring& coloring,
                        const StiffnessLayout& layout, std::span<const std::int32_t> equation,
                        double mass_coefficient, std::span<double> values) {
  const kernels::PlaneKind plane = plane_kind(model.plane);
  const double t = model.thickness;
  std::fill(values.begin(), values.end(), 0.0);
  for (std::int32_t c = 0; c < coloring.num_colors(); ++c) {
    tbb::parallel_for(
        tbb::blocked_range<std::int32_t>(coloring.offset[c], coloring.offset[c + 1], 256),
        [&](auto range) {
          for (std::int32_t i = range.begin(); i != range.end(); ++i) {
            const std::int32_t e = coloring.element[i];
            double xy[6], d[9], k[36];
            gather_element(model.conn, e, model.X, xy);
            kernels::elasticity_matrix(damaged_young(model.young[e], model.damage[e]),
                                       model.poisson[e], plane, d);
            kernels::cst_stiffness(xy, d, t, k);
            // Co-rotational: the reference stiffness turned into the element's frame.
            if (!model.rotation.empty() && model.rotation[e] != 0.0)
              kernels::rotate_element_matrix(kernels::Rotation(model.rotation[e]), k);
            const std::int32_t* to =
                &layout.scatter[static_cast<std::size_t>(e) * kElementUpperEntries];
            for (int a = 0; a < 6; ++a)
              for (int b = a; b < 6; ++b, ++to)
                if (*to >= 0) values[*to] += k[6 * a + b];
          }
        });
  }
  if (mass_coefficient != 0.0) {
    const auto num_nodes = model.num_nodes();
    tbb::parallel_for(std::int32_t{0}, num_nodes, [&](std::int32_t n) {
      for (int c = 0; c < 2; ++c) {
        const std::int32_t eq = equation[2 * n + c];
        if (eq >= 0) values[layout.diagonal[eq]] += mass_coefficient * model.node_mass[n];
      }
    });
  }
}

}  // namespace rockdd

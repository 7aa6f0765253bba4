#include "engine/assembly/internal_force.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

#include "engine/assembly/element_state.hpp"

namespace rockdd {

void compute_internal_force(const Model& model, const ElementColoring& coloring,
                            std::span<const double> u, std::span<double> strain,
                            std::span<double> stress, std::span<double> f_int) {
  const kernels::PlaneKind plane = plane_kind(model.plane);
  const double t = model.thickness;
  std::fill(f_int.begin(), f_int.end(), 0.0);
  for (std::int32_t c = 0; c < coloring.num_colors(); ++c) {
    tbb::parallel_for(
        tbb::blocked_range<std::int32_t>(coloring.offset[c], coloring.offset[c + 1], 512),
        [&](auto range) {
          for (std::int32_t i = range.begin(); i != range.end(); ++i) {
            const std::int32_t e = coloring.element[i];
            double xy[6], ue[6], d[9], f[6];
            gather_element(model.conn, e, model.X, xy);
            gather_element(model.conn, e, u, ue);
            kernels::elasticity_matrix(damaged_young(model.young[e], model.damage[e]),
                                       model.poisson[e], plane, d);
            double* eps = &strain[3 * static_cast<std::size_t>(e)];
            double* sig = &stress[3 * static_cast<std::size_t>(e)];
            kernels::cst_strain(xy, ue, eps);
            kernels::cst_stress(d, eps, sig);
            kernels::cst_internal_force(xy, sig, t, f);
            for (int k = 0; k < 3; ++k) {
              const std::int32_t n = model.conn[3 * e + k];
              f_int[2 * n] += f[2 * k];
              f_int[2 * n + 1] += f[2 * k + 1];
            }
          }
        });
  }
}

double strain_energy(const Model& model, std::span<const double> strain,
                     std::span<const double> stress) {
  // Summed serially in element order: the value must not depend on the thread count.
  double energy = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const double* eps = &strain[3 * static_cast<std::size_t>(e)];
    const double* sig = &stress[3 * static_cast<std::size_t>(e)];
    energy += 0.5 * (sig[0] * eps[0] + sig[1] * eps[1] + sig[2] * eps[2]) * model.area0[e];
  }
  return energy * model.thickness;
}

}  // namespace rockdd

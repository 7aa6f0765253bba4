#include "engine/time/snap_back.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/cst.hpp"

namespace rockdd {

bool cascade_calls_for_inertia(const FractureSpec& fracture, Analysis analysis, int pass) {
  return fracture.snap_back == FractureSpec::SnapBack::dynamic &&
         analysis == Analysis::quasi_static && pass >= 2;
}

double snap_back_time_step(const Scene& scene, const Model& model) {
  if (scene.fracture.snap_back_dt) return *scene.fracture.snap_back_dt;
  // A quarter of the transit time: a crack, no faster than the Rayleigh wave (about 0.6 of
  // the dilatational one), runs at most a sixth of an element a step.
  constexpr double kTransitFraction = 0.25;
  double shortest = std::numeric_limits<double>::infinity();
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    double longest_edge = 0.0;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = model.conn[3 * e + k], b = model.conn[3 * e + (k + 1) % 3];
      longest_edge = std::max(longest_edge, std::hypot(model.X[2 * b] - model.X[2 * a],
                                                       model.X[2 * b + 1] - model.X[2 * a + 1]));
    }
    const double height = 2.0 * model.area0[e] / longest_edge;
    // The in-plane dilatational wave's modulus: D11 of the element's elasticity.
    const double modulus =
        kernels::isotropic_moduli(model.young[e], model.poisson[e], model.plane).normal;
    shortest = std::min(shortest, height / std::sqrt(modulus / model.density[e]));
  }
  return kTransitFraction * shortest;
}

}  // namespace rockdd

#include "engine/damage/damage_stage.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "engine/assembly/element_state.hpp"

namespace rockdd {

DamageStage::DamageStage(const Scene& scene, const Model& model) : plane_(plane_kind(model.plane)) {
  for (const MaterialSpec& m : scene.materials) {
    kernels::DamageParams p;
    p.poisson = m.poisson;
    p.lambda = m.residual;
    p.eta = m.ultimate_strain;
    p.onset = m.tension_onset == TensionOnset::strain ? kernels::TensionOnset::strain
                                                      : kernels::TensionOnset::stress;
    p.floor = kDamagedStiffnessFloor;
    params_.push_back(p);
    damageable_.push_back(m.has_damage() ? 1 : 0);
    detach_at_.push_back(m.detach_at_damage);
  }
}

double DamageStage::detach_threshold(const Model& model, std::int32_t e) const {
  return detach_at_[static_cast<std::size_t>(model.element_material[e])];
}

DamageChange DamageStage::evaluate(Model& model) const {
  using Range = tbb::blocked_range<std::int32_t>;
  return tbb::parallel_reduce(
      Range(0, model.num_elements(), 1024), DamageChange{},
      [&](const Range& range, DamageChange change) {
        for (std::int32_t e = range.begin(); e != range.end(); ++e) {
          const auto mi = static_cast<std::size_t>(model.element_material[e]);
          if (!damageable_[mi]) continue;
          kernels::DamageParams p = params_[mi];
          p.young = model.young[e];
          p.ft0 = model.tensile_strength[e];
          p.fc0 = model.compressive_strength[e];
          p.phi = model.friction_angle[e];
          const double w_old = model.damage[e];
          const kernels::DamageUpdate update = kernels::evaluate_damage(
              &model.strain[3 * static_cast<std::size_t>(e)],
              &model.stress[3 * static_cast<std::size_t>(e)], p, plane_, w_old);
          if (update.w > w_old) {
            model.damage[e] = update.w;
            ++change.grown;
            if (w_old == 0.0) ++change.newly_damaged;
          }
        }
        return change;
      },
      [](DamageChange a, const DamageChange& b) {
        a.newly_damaged += b.newly_damaged;
        a.grown += b.grown;
        return a;
      });
}

}  // namespace rockdd

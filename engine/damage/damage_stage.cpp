#include "engine/damage/damage_stage.hpp"

#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "engine/assembly/element_state.hpp"
#include "engine/common/errors.hpp"

namespace rockdd {

DamageStage::DamageStage(const Scene& scene, const Model& model)
    : plane_(model.plane), separation_(model) {
  for (const MaterialSpec& m : scene.materials) {
    kernels::DamageParams p;
    p.poisson = m.poisson;
    p.lambda = m.residual;
    p.eta = m.ultimate_strain;
    p.onset = m.tension_onset;
    p.floor = kernels::kStiffnessFloor;
    params_.push_back(p);
    damageable_.push_back(m.has_damage() ? 1 : 0);
    detach_at_.push_back(m.detach_at_damage);
    fracture_energy_.push_back(m.fracture_energy.value_or(0.0));
  }
  check_crack_band(scene, model);
  // Two sines an element and a pass were 2 % of a UCS run: the factor is kept per element.
  mohr_coulomb_.resize(static_cast<std::size_t>(model.num_elements()));
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    mohr_coulomb_[static_cast<std::size_t>(e)] =
        kernels::mohr_coulomb_factor(model.friction_angle[e]);
}

void DamageStage::check_crack_band(const Scene& scene, const Model& model) const {
  // The widest element against its own limit: heterogeneous strengths move the limit too.
  std::int32_t worst = -1;
  double worst_excess = 1.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const double gf = fracture_energy_[static_cast<std::size_t>(model.element_material[e])];
    if (gf <= 0.0) continue;
    const double h = kernels::crack_band_width(std::abs(model.area0[e]));
    const double limit =
        kernels::crack_band_max_width(gf, model.tensile_strength[e], model.young[e]);
    if (h / limit > worst_excess) {
      worst_excess = h / limit;
      worst = e;
    }
  }
  if (worst < 0) return;
  const auto m = static_cast<std::size_t>(model.element_material[worst]);
  const double gf = fracture_energy_[m];
  const double limit =
      kernels::crack_band_max_width(gf, model.tensile_strength[worst], model.young[worst]);
  char text[512];
  std::snprintf(text, sizeof text,
                "expected every element narrower than the crack band limit 2 E0 G_f / ft0^2, "
                "but element %d is %.4g m wide (sqrt(2 A)) against %.4g m (E0 = %.4g Pa, "
                "ft0 = %.4g Pa, G_f = %.4g J/m^2): it would snap back on its own. Refine the "
                "mesh (element_size below %.3g m) or raise fracture_energy",
                static_cast<int>(worst), kernels::crack_band_width(std::abs(model.area0[worst])),
                limit, model.young[worst], model.tensile_strength[worst], gf,
                // An equilateral triangle of side a is sqrt(sqrt(3)/2) a wide.
                limit / std::sqrt(std::sqrt(3.0) / 2.0));
  throw InputError(scene.file.string(), "material[" + std::to_string(m) + "].fracture_energy",
                   text);
}

double DamageStage::detach_threshold(const Model& model, std::int32_t e) const {
  return detach_at_[static_cast<std::size_t>(model.element_material[e])];
}

kernels::DamageParams DamageStage::element_params(const Model& model, std::int32_t e) const {
  kernels::DamageParams p = params_[static_cast<std::size_t>(model.element_material[e])];
  p.young = model.young[e];
  p.ft0 = model.tensile_strength[e];
  p.fc0 = model.compressive_strength[e];
  p.mohr_coulomb = mohr_coulomb_[static_cast<std::size_t>(e)];
  const double gf = fracture_energy_[static_cast<std::size_t>(model.element_material[e])];
  if (gf > 0.0) {
    p.eta = kernels::crack_band_ultimate_strain(
        gf, kernels::crack_band_width(std::abs(model.area0[e])), p.ft0, p.young, p.lambda);
  }
  return p;
}

OnsetSearch DamageStage::locate_onset(const Model& model, std::span<const double> strain0,
                                      std::span<const double> stress0, double target) const {
  using Range = tbb::blocked_range<std::int32_t>;
  struct Found {
    double largest = 0.0;
    double fraction = 2.0;  // earliest crossing; > 1: none
    bool at_start = false;  // an element past the target at the step's start
  };
  auto ratio_at = [&](std::int32_t e, const kernels::DamageParams& p, double f) {
    const auto i = 3 * static_cast<std::size_t>(e);
    if (f == 1.0) return kernels::onset_ratio(&model.strain[i], &model.stress[i], p, plane_, 0.0);
    double eps[3], sig[3];
    for (int k = 0; k < 3; ++k) {
      eps[k] = strain0[i + k] + f * (model.strain[i + k] - strain0[i + k]);
      sig[k] = stress0[i + k] + f * (model.stress[i + k] - stress0[i + k]);
    }
    return kernels::onset_ratio(eps, sig, p, plane_, 0.0);
  };
  // Max and min do not depend on the order: the search is the same on any thread count.
  const Found found = tbb::parallel_reduce(
      Range(0, model.num_elements(), 1024), Found{},
      [&](const Range& range, Found top) {
        for (std::int32_t e = range.begin(); e != range.end(); ++e) {
          if (!damageable_[static_cast<std::size_t>(model.element_material[e])] ||
              model.damage[e] > 0.0)
            continue;
          const kernels::DamageParams p = element_params(model, e);
          const double end = ratio_at(e, p, 1.0);
          top.largest = std::max(top.largest, end);
          if (end <= target) continue;
          if (ratio_at(e, p, 0.0) >= target) {
            top.at_start = true;
            continue;
          }
          // The ratio along the step is continuous: bisection to 2^-52 of the step.
          double below = 0.0, above = 1.0;
          for (int k = 0; k < 52 && below < above; ++k) {
            const double mid = 0.5 * (below + above);
            (ratio_at(e, p, mid) < target ? below : above) = mid;
          }
          top.fraction = std::min(top.fraction, above);
        }
        return top;
      },
      [](Found a, const Found& b) {
        a.largest = std::max(a.largest, b.largest);
        a.fraction = std::min(a.fraction, b.fraction);
        a.at_start = a.at_start || b.at_start;
        return a;
      });
  OnsetSearch search{found.largest, std::nullopt};
  if (found.at_start)
    search.fraction = 0.0;
  else if (found.fraction <= 1.0)
    search.fraction = found.fraction;
  return search;
}

DamageChange DamageStage::evaluate(Model& model, double band, bool start_onsets) {
  using Range = tbb::blocked_range<std::int32_t>;
  const std::int32_t num_elements = model.num_elements();
  // The onset ratios order the onsets a pass starts; a pass that starts none reads no ratio.
  if (start_onsets) ratio_.assign(static_cast<std::size_t>(num_elements), 0.0);
  // The largest onset ratio among undamaged elements: a max does not depend on the order.
  double largest = 0.0;
  if (start_onsets)
    largest = tbb::parallel_reduce(
        Range(0, num_elements, 1024), 0.0,
        [&](const Range& range, double top) {
          for (std::int32_t e = range.begin(); e != range.end(); ++e) {
            if (!damageable_[static_cast<std::size_t>(model.element_material[e])] ||
                model.damage[e] > 0.0)
              continue;
            const auto i = 3 * static_cast<std::size_t>(e);
            ratio_[e] = kernels::onset_ratio(&model.strain[i], &model.stress[i],
                                             element_params(model, e), plane_, 0.0);
            top = std::max(top, ratio_[e]);
          }
          return top;
        },
        [](double a, double b) { return std::max(a, b); });
  const double event = largest / (1.0 + band);
  return tbb::parallel_reduce(
      Range(0, num_elements, 1024), DamageChange{},
      [&](const Range& range, DamageChange change) {
        for (std::int32_t e = range.begin(); e != range.end(); ++e) {
          if (!damageable_[static_cast<std::size_t>(model.element_material[e])]) continue;
          const double w_old = model.damage[e];
          // An undamaged element short of its onset cannot start damage (a law fires only at
          // ratio >= 1; the margin covers the ratio's own rounding): most elements, most passes.
          if (w_old == 0.0 && (!start_onsets || ratio_[e] < 1.0 - 1e-9)) continue;
          const auto i = 3 * static_cast<std::size_t>(e);
          const kernels::DamageUpdate update = kernels::evaluate_damage(
              &model.strain[i], &model.stress[i], element_params(model, e), plane_, w_old);
          if (update.w <= w_old) continue;
          if (w_old == 0.0 && ratio_[e] < event) {
            ++change.deferred;
            continue;
          }
          model.damage[e] = update.w;
          ++change.grown;
          if (w_old == 0.0)
            ++change.newly_damaged;
          else
            change.largest_growth =
                std::max(change.largest_growth, (update.w - w_old) / (1.0 - w_old));
        }
        return change;
      },
      [](DamageChange a, const DamageChange& b) {
        a.newly_damaged += b.newly_damaged;
        a.grown += b.grown;
        a.deferred += b.deferred;
        a.largest_growth = std::max(a.largest_growth, b.largest_growth);
        return a;
      });
}

}  // namespace rockdd

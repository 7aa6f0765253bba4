#pragma once
// Elastic damage of the rock elements (METHOD.md "Elastic damage"): the laws of
// kernels/damage_law.hpp evaluated on every damageable element after a solve. Built only for
// scenes whose materials give a strength.
#include <cstdint>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"
#include "kernels/damage_law.hpp"

namespace rockdd {

/// What one evaluation did.
struct DamageChange {
  std::int32_t newly_damaged = 0;  // elements whose damage started (w was 0)
  std::int32_t grown = 0;          // elements whose damage grew
  std::int32_t deferred = 0;       // past their onset but outside the event's band: left for
                                   // the next pass, which may find them unloaded
};

/// Per-material law parameters, and the evaluation over all elements.
class DamageStage {
 public:
  DamageStage(const Scene& scene, const Model& model);

  /// Raises model.damage where the laws, at the element strain and stress in `model`, give
  /// more (damage never decreases). Damage grows in every element already damaged, but starts
  /// only in the undamaged elements whose onset ratio is within `band` of the largest
  /// (ratio >= max / (1 + band)): a damage event, after which the step is re-solved, so an
  /// element that its neighbours' failure unloads does not fail with them. Deterministic.
  DamageChange evaluate(Model& model, double band);

  /// The damage at which an element detaches, per element (scene's detach_at_damage).
  double detach_threshold(const Model& model, std::int32_t e) const;

 private:
  /// The law parameters of element e, with its drawn modulus and strengths.
  kernels::DamageParams element_params(const Model& model, std::int32_t e) const;

  /// Refuses (InputError, exit 2) a mesh with an element too wide for its crack band.
  void check_crack_band(const Scene& scene, const Model& model) const;

  std::vector<kernels::DamageParams> params_;  // per material, strengths filled per element
  std::vector<double> mohr_coulomb_;           // per element: mohr_coulomb_factor(friction angle)
  std::vector<std::uint8_t> damageable_;       // per material
  std::vector<double> detach_at_;              // per material
  std::vector<double> fracture_energy_;        // per material: G_f, 0 = no crack band
  kernels::PlaneKind plane_;
  std::vector<double> ratio_;  // per element: onset ratio of an undamaged element, else 0
};

}  // namespace rockdd

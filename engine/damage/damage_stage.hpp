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
};

/// Per-material law parameters, and the evaluation over all elements.
class DamageStage {
 public:
  DamageStage(const Scene& scene, const Model& model);

  /// Raises model.damage where the laws, at the element strain and stress in `model`, give
  /// more (damage never decreases). Deterministic (each element on its own).
  DamageChange evaluate(Model& model) const;

  /// The damage at which an element detaches, per element (scene's detach_at_damage).
  double detach_threshold(const Model& model, std::int32_t e) const;

 private:
  std::vector<kernels::DamageParams> params_;  // per material, strengths filled per element
  std::vector<std::uint8_t> damageable_;       // per material
  std::vector<double> detach_at_;              // per material
  kernels::PlaneKind plane_;
};

}  // namespace rockdd

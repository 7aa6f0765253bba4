#pragma once
// Elastic damage of the rock elements (METHOD.md "Elastic damage"): the laws of
// kernels/damage_law.hpp evaluated on every damageable element after a solve. Built only for
// scenes whose materials give a strength.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/damage/separation.hpp"
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
  // The largest growth of an element already damaged, (w_new - w_old) / (1 - w_old): the
  // relative fall of its modulus, and so the relative excess of the stress it carried.
  double largest_growth = 0.0;
};

/// Where a step meets its first onset (DamageStage::locate_onset).
struct OnsetSearch {
  double largest = 0.0;  // the largest onset ratio of an undamaged element at the step's end
  // The fraction of the step [0, 1] at which the first undamaged element's ratio reaches the
  // target, strain and stress taken along the straight path from the step's start (0: one
  // that passes it stood past it already at the start); unset when none passes it.
  std::optional<double> fraction;
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
  /// Without `start_onsets`, damage only grows where it has started (onsets are left for the
  /// caller to locate, DamageStage::locate_onset).
  DamageChange evaluate(Model& model, double band, bool start_onsets = true);

  /// The undamaged elements' onset ratios at the model's strain and stress (the step's end),
  /// and where along the step from `strain0` and `stress0` (its start, 3 per element) the
  /// first of them reaches `target`: each element's crossing by bisection of its ratio along
  /// the straight path (a linear response is straight), the earliest over all elements.
  /// Deterministic; leaves the model as it is.
  OnsetSearch locate_onset(const Model& model, std::span<const double> strain0,
                           std::span<const double> stress0, double target) const;

  /// The damage at which an element detaches, per element (scene's detach_at_damage).
  double detach_threshold(const Model& model, std::int32_t e) const;

  /// The intact parts of the model as it was built (separation.hpp).
  const SeparationWatch& separation() const { return separation_; }

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
                               // (as the last pass that started onsets found them)
  SeparationWatch separation_;
};

}  // namespace rockdd

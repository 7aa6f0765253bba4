#pragma once
// Small per-element helpers shared by assembly and stress recovery.
#include <algorithm>
#include <cstdint>
#include <span>

#include "engine/model/model.hpp"
#include "kernels/cst.hpp"

namespace rockdd {

/// Stiffness of a fully damaged element, as a fraction of E0: keeps the system regular.
inline constexpr double kDamagedStiffnessFloor = 1e-6;

/// Plane mode of the scene in the kernels' terms.
inline kernels::PlaneKind plane_kind(PlaneMode mode) {
  return mode == PlaneMode::strain ? kernels::PlaneKind::strain : kernels::PlaneKind::stress;
}

/// E = (1 - w) E0, never below the floor (paper eq. 2).
inline double damaged_young(double young0, double damage) {
  return young0 * std::max(1.0 - damage, kDamagedStiffnessFloor);
}

/// Gathers the 6 coordinates of element e from a 2-per-node array.
inline void gather_element(std::span<const std::int32_t> conn, std::int32_t e,
                           std::span<const double> field, double out[6]) {
  for (int k = 0; k < 3; ++k) {
    const std::int32_t n = conn[3 * e + k];
    out[2 * k] = field[2 * n];
    out[2 * k + 1] = field[2 * n + 1];
  }
}

}  // namespace rockdd

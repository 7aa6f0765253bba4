#pragma once
// What every stage means by an element's material: the plane kind, the damaged modulus with
// its floor, and the test that starts tensile damage. Defined here once; the scene, assembly,
// damage and time stages all use these.
#include <algorithm>

namespace rockdd::kernels {

/// Plane stress or plane strain: selects the elasticity matrix.
enum class PlaneKind { stress, strain };

/// Which test starts tensile damage: major principal stress >= ft0, or eps_bar >= ft0/E0.
enum class TensionOnset { stress, strain };

/// Stiffness a fully damaged element keeps, as a fraction of E0: the system stays regular.
inline constexpr double kStiffnessFloor = 1e-6;

/// E = (1 - w) E0, never below floor x E0 (paper eq. 2).
inline double damaged_modulus(double young0, double w, double floor = kStiffnessFloor) {
  return young0 * std::max(1.0 - w, floor);
}

}  // namespace rockdd::kernels

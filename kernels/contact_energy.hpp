#pragma once
// The normal force of a penalty contact averaged over a time step so that its work is the
// energy its spring releases (the discrete gradient of the spring energy, Gonzalez 1996;
// Armero and Petocz 1998). Newmark's average acceleration takes the mean of the step's end
// forces instead, which is exact for a spring closed over the whole step but, for one that
// opens within it, pushes over the whole step with the force it had at the start and so gives
// back more than the spring held (docs/method-choices.md, "Newmark and contacts").

namespace rockdd::kernels {

/// Mean normal force over a step and its derivative in the end gap.
struct MeanNormalForce {
  double force = 0;  // N: kn g for a closed spring at gap g (< 0 pressed), as the body pushes it
  double stiffness = 0;  // d force / d g1, N/m
};

/// The mean normal force (Phi(g1) - Phi(g0)) / (g1 - g0) of a contact whose spring
/// (energy Phi = kn g^2 / 2 while closed, 0 open) is closed at the start of the step or not
/// (`closed_at_start`, gap g0) and at its end or not (`closed_at_end`, gap g1):
///  - closed at both ends: kn (g0 + g1) / 2, the trapezoid (exact for a linear spring);
///  - opening (g0 < 0 < g1): -kn g0^2 / (2 (g1 - g0)), the force at the start times the share
///    of the step before the gap crosses zero, halved;
///  - closing (g0 > 0 > g1): kn g1^2 / (2 (g1 - g0)), likewise with the end force.
/// A spring that opens from tension (g0 >= 0) or is taken open while still pressed (g1 <= 0)
/// gives no force: what it held is lost, never made. One closed at its end in tension, or
/// closed at its end though pressed at a start where it was open, keeps Newmark's mean
/// kn g1 / 2. Both derivatives lie in [0, kn / 2], so the average stays a spring.
MeanNormalForce mean_normal_force(bool closed_at_start, bool closed_at_end, double g0, double g1,
                                  double kn);

}  // namespace rockdd::kernels

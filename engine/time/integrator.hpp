#pragma once
// Time integration on lumped masses. Both schemes solve
//   (K + c M) du = F - f_int(u_n) + M (p v_n + q a_n)
// and then update velocity (and acceleration) from du:
//  - DDA (Shi): constant acceleration over the step, c = 2/dt^2, p = 2/dt, q = 0,
//    v_{n+1} = 2 du/dt - v_n. Damps high frequencies (ratio about (omega dt)/4).
//  - Newmark average acceleration (beta = 1/4, gamma = 1/2): c = 4/dt^2, p = 4/dt, q = 1,
//    a_{n+1} = 4 du/dt^2 - 4 v_n/dt - a_n, v_{n+1} = v_n + dt/2 (a_n + a_{n+1}). No damping.
// "static" drops the mass (c = p = q = 0); "quasi-static" starts every step at rest.
#include <span>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// Coefficients of the effective system for one step.
struct InertiaTerms {
  double mass_coefficient = 0;          // c
  double velocity_coefficient = 0;      // p
  double acceleration_coefficient = 0;  // q
};

/// The coefficients of `integrator` for a step of length dt in `analysis`.
InertiaTerms inertia_terms(Analysis analysis, Integrator integrator, double dt);

/// Velocity (and acceleration) of free dofs after a step with increment du.
/// Prescribed dofs take their imposed velocity and zero acceleration. Returns, in a dynamic
/// analysis, the energy the scheme damped in the step: the net force's trapezoidal work over
/// du, sum m (a_n + a_{n+1}) du / 2 over free dofs, less the kinetic energy it gained. Zero
/// for Newmark's average acceleration (to round-off); m (a_n - a_{n+1}) du / 2 for DDA's.
double update_velocity(Analysis analysis, Integrator integrator, double dt,
                       std::span<const double> du, std::span<const std::uint8_t> prescribed,
                       std::span<const double> imposed_velocity, std::span<const double> node_mass,
                       std::span<double> v, std::span<double> a);

/// The energy a step's mass term c M holds at increment du: (c/2) sum m du^2 over the free
/// dofs. Without inertia it is the work the step's loads did beyond what the body stores,
/// which the next step, starting at rest, discards.
double mass_term_energy(double mass_coefficient, std::span<const double> du,
                        std::span<const std::uint8_t> prescribed,
                        std::span<const double> node_mass);

}  // namespace rockdd

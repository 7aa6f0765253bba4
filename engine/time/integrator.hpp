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

/// What DDA's scheme loses through contact forces beyond the share update_velocity books.
/// DDA's velocity update makes the kinetic energy change the work of the step's end forces,
/// exactly, so the contacts take f_c,end . du from the body (the trapezoid on prescribed dofs,
/// whose work the reactions book): at a landing, springs that close within the step carry
/// their end force over all of it, and that is the impact's loss. update_velocity's trapezoid
/// books (f_c,end - f_c,start) . du / 2 of it on the free dofs. Returns the difference, where
/// the contacts' loss (what they took less their springs' energy gain and the friction booked)
/// is positive; where it is negative the contacts made energy, and none of that is booked as
/// a loss: the balance's unaccounted shows it. `f_contact_end` is what the step's last solve
/// had its contacts push with (before its last update switched any), `f_contact_start` the
/// last step's; both as internal forces (what the body pushes the springs with).
double contact_end_point_loss(std::span<const double> f_contact_end,
                              std::span<const double> f_contact_start, std::span<const double> du,
                              std::span<const std::uint8_t> prescribed, double spring_energy_gain,
                              double friction);

/// The energy a step's mass term c M holds at increment du: (c/2) sum m du^2 over the free
/// dofs. Without inertia it is the work the step's loads did beyond what the body stores,
/// which the next step, starting at rest, discards.
double mass_term_energy(double mass_coefficient, std::span<const double> du,
                        std::span<const std::uint8_t> prescribed,
                        std::span<const double> node_mass);

}  // namespace rockdd

#include "engine/time/integrator.hpp"

#include <algorithm>
#include <cstdint>

namespace rockdd {

InertiaTerms inertia_terms(Analysis analysis, Integrator integrator, double dt) {
  if (analysis == Analysis::static_) return {};
  const bool newmark = integrator == Integrator::newmark;
  InertiaTerms terms;
  terms.mass_coefficient = (newmark ? 4.0 : 2.0) / (dt * dt);
  if (analysis == Analysis::dynamic) {
    terms.velocity_coefficient = (newmark ? 4.0 : 2.0) / dt;
    terms.acceleration_coefficient = newmark ? 1.0 : 0.0;
  }
  return terms;
}

double update_velocity(Analysis analysis, Integrator integrator, double dt,
                       std::span<const double> du, std::span<const std::uint8_t> prescribed,
                       std::span<const double> imposed_velocity, std::span<const double> node_mass,
                       std::span<double> v, std::span<double> a) {
  double damped = 0.0;  // serially in dof order: the total must not depend on threads
  for (std::size_t d = 0; d < du.size(); ++d) {
    if (prescribed[d]) {
      v[d] = imposed_velocity[d];
      a[d] = 0.0;
      continue;
    }
    switch (analysis) {
      case Analysis::static_:
        v[d] = 0.0;
        a[d] = 0.0;
        break;
      case Analysis::quasi_static:  // the step's mean velocity; the next step starts at rest
        // A step of no length (the damage of an onset located at the step before) moves
        // nodes without time: no velocity, and the next step starts at rest as always.
        v[d] = dt > 0.0 ? du[d] / dt : 0.0;
        a[d] = 0.0;
        break;
      case Analysis::dynamic: {
        const double v_old = v[d], a_old = a[d];
        if (integrator == Integrator::newmark) {
          const double a_new = 4.0 * du[d] / (dt * dt) - 4.0 * v[d] / dt - a[d];
          v[d] += 0.5 * dt * (a[d] + a_new);
          a[d] = a_new;
        } else {
          const double v_new = 2.0 * du[d] / dt - v[d];
          a[d] = (v_new - v[d]) / dt;
          v[d] = v_new;
        }
        damped +=
            node_mass[d / 2] * (0.5 * (a_old + a[d]) * du[d] - 0.5 * (v[d] * v[d] - v_old * v_old));
        break;
      }
    }
  }
  return damped;
}

double mass_term_energy(double mass_coefficient, std::span<const double> du,
                        std::span<const std::uint8_t> prescribed,
                        std::span<const double> node_mass) {
  double energy = 0.0;  // serially in dof order: the total must not depend on threads
  for (std::size_t d = 0; d < du.size(); ++d)
    if (!prescribed[d]) energy += node_mass[d / 2] * du[d] * du[d];
  return 0.5 * mass_coefficient * energy;
}

double contact_end_point_loss(std::span<const double> f_contact_end,
                              std::span<const double> f_contact_start, std::span<const double> du,
                              std::span<const std::uint8_t> prescribed, double spring_energy_gain,
                              double friction) {
  double taken = 0.0, booked = 0.0;  // serially in dof order: totals must not depend on threads
  for (std::size_t d = 0; d < du.size(); ++d) {
    if (prescribed[d]) {
      taken += 0.5 * (f_contact_start[d] + f_contact_end[d]) * du[d];
    } else {
      taken += f_contact_end[d] * du[d];
      booked += 0.5 * (f_contact_end[d] - f_contact_start[d]) * du[d];
    }
  }
  const double loss = taken - spring_energy_gain - friction;
  return std::max(loss, 0.0) - booked;
}

}  // namespace rockdd

#pragma once
// The energy a run accounts for beside what its state holds (strain and kinetic energy): the
// work done on it and where energy left it. The totals belong to the committed state; a step
// attempt gathers its own damage and snap-back terms apart (StepEnergy), which the commit adds.
namespace rockdd {

/// What one step attempt released by damage and re-solves (J per the scene's thickness).
struct StepEnergy {
  double damage = 0.0;     // released by this attempt's modulus drops
  double snap_back = 0.0;  // released by its re-solves, see EnergyAccount::snap_back
  double created = 0.0;    // what its re-solves gained instead of released, as a positive number
  // Without inertia: what its first solve put into the mass term (EnergyAccount::quasi_static).
  double quasi_static = 0.0;

  /// Adds one re-solve's release (negative: energy it created).
  void add_snap_back(double released) {
    snap_back += released;
    if (released < 0.0) created -= released;
  }
};

/// Running totals of the energy balance over the committed steps (J per the thickness).
struct EnergyAccount {
  double initial = 0.0;        // kinetic and strain energy at step 0 (initial motion, stress)
  double external_work = 0.0;  // loads and constraints
  double damage = 0.0;         // released by modulus drops at fixed strain (eq. 3 and 7)
  double snap_back = 0.0;      // released when the rock re-settles after damage
  double anchor = 0.0;         // held by the fragment restraint when steps ended
  double integrator = 0.0;     // damped by the time integrator (DDA's scheme; dynamic only)
  double friction = 0.0;       // work of friction: shear force times the slip its anchor followed
  // The quasi-static scheme's own loss: the work its mass term c M (c = 2/dt^2) took in a step,
  // (c/2) du^T M du, which the velocity reset discards; a dynamic run turns it into motion.
  double quasi_static = 0.0;
  // Of snap_back, what re-solves gained instead of released: energy the scheme created, which
  // a sound re-solve never does.
  double created = 0.0;

  /// Adds a committed attempt's damage and snap-back terms.
  void add(const StepEnergy& step) {
    damage += step.damage;
    snap_back += step.snap_back;
    created += step.created;
    quasi_static += step.quasi_static;
  }
};

}  // namespace rockdd

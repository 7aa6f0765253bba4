#pragma once
// The energy a run accounts for beside what its state holds (strain and kinetic energy): the
// work done on it and where energy left it. Terms of the step being attempted are kept apart
// until the step commits, so a redone step forgets them.
namespace rockdd {

/// Running totals of the energy balance (J per the scene's thickness).
struct EnergyAccount {
  double external_work = 0.0;  // loads and constraints, committed steps
  double damage = 0.0;         // released by modulus drops at fixed strain (eq. 3 and 7)
  double snap_back = 0.0;      // released when the rock re-settles after damage, see below
  double anchor = 0.0;         // held by the fragment restraint when steps ended
  double integrator = 0.0;     // damped by the time integrator (DDA's scheme; dynamic only)
  // Of snap_back, what re-solves gained instead of released (their negative terms, as a
  // positive number): energy the scheme created, which a sound re-solve never does.
  double created = 0.0;

  // The step being attempted.
  double attempt_damage = 0.0, attempt_snap_back = 0.0, attempt_created = 0.0;

  /// Adds one re-solve's release (negative: energy it created) to the attempt.
  void add_snap_back(double released) {
    attempt_snap_back += released;
    if (released < 0.0) attempt_created -= released;
  }
  void begin_attempt() { attempt_damage = attempt_snap_back = attempt_created = 0.0; }
  void commit_attempt() {
    damage += attempt_damage;
    snap_back += attempt_snap_back;
    created += attempt_created;
  }
};

}  // namespace rockdd

#pragma once
// What a run did and where its time went, one plain struct per concern (in the spirit of
// Box2D's b2Profile and counters). Each stage adds to its own; run_summary writes them all
// into summary.json.
#include <optional>

#include "engine/common/timers.hpp"
#include "engine/damage/disintegration.hpp"
#include "engine/report/softening_monitor.hpp"

namespace rockdd {

/// Counters of one run.
struct RunStats {
  long steps = 0;                     // committed steps
  long redone_steps = 0;              // attempts redone with a smaller dt, for any of:
  long redone_by_open_close = 0;      //   the open-close iteration did not settle
  long redone_by_displacement = 0;    //   an increment past max_step_displacement or the reach
  long redone_by_energy = 0;          //   the step created energy (EnergyCheck)
  long onset_cuts = 0;                // attempts cut back to the first onset they passed
  long located_onsets = 0;            // steps that ended at an onset (each followed by one of
                                      // no length, where that onset's damage runs)
  long dt_changes = 0;                // changes of dt by the step control
  long open_close_iterations = 0;     // over all steps
  long max_open_close_per_step = 0;   // the most one step needed
  long open_close_relaxed_steps = 0;  // steps that settled only with a widened tolerance
  double largest_relaxation = 1.0;    // the widest tolerance factor such a step needed
  long damage_iterations = 0;         // re-solves after a damage event
  long damage_stage_passes = 0;       // passes of the damage stage over every element (law
                                      // evaluations and onset searches)
  long damage_limit_hits = 0;         // steps that ran out of damage passes
  long detached_elements = 0;         // elements that became blocks of their own
  long parts_cut_loose = 0;           // damage passes after which the fragment restraint grew
  long restraint_relaxations = 0;     // solves that re-anchored the restraint (relax_restraint)
  long frame_corrections = 0;  // Newton solves after elements turned past K's frames in a solve
};

/// Where a quasi-static run went on with inertia (fracture.snap_back = "dynamic").
struct InertiaSwitch {
  long step = 0;  // the last quasi-static step
  double time = 0.0;
  double dt = 0.0;  // of the dynamic steps after it
};

/// The run's counters, timers and monitors.
struct RunReport {
  RunStats counters;
  StageTimers timers;        // the steps' stages
  SetupTimers setup_timers;  // building the Simulation
  SofteningMonitor softening;
  std::optional<InertiaSwitch> inertia_switch;
  std::optional<Disintegration> disintegration;  // the quasi-static specimen fell apart
  bool stopped_by_caller = false;  // RunOptions::keep_going said false
};

}  // namespace rockdd

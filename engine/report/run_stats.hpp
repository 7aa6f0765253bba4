#pragma once
// What a run did, counted as it goes (in the spirit of Box2D's b2Profile and counters): steps,
// redos, open-close and damage iterations, fractures. summary.json reports them.
#include <nlohmann/json.hpp>

namespace rockdd {

/// Counters of one run; each stage adds to its own.
struct RunStats {
  long steps = 0;                     // committed steps
  long redone_steps = 0;              // attempts redone with a smaller dt
  long open_close_iterations = 0;     // over all steps
  long max_open_close_per_step = 0;   // the most one step needed
  long open_close_relaxed_steps = 0;  // steps that settled only with a widened tolerance
  double largest_relaxation = 1.0;    // the widest tolerance factor such a step needed
  long damage_iterations = 0;         // re-solves after a damage event
  long damage_limit_hits = 0;         // steps that ran out of damage passes
  long detached_elements = 0;         // elements that became blocks of their own
  long parts_cut_loose = 0;           // damage passes after which the fragment restraint grew

  /// Writes the counters under their summary.json keys (docs/scene-extensions.md).
  void write(nlohmann::json& summary) const;
};

}  // namespace rockdd

#pragma once
// Moments inside a step that a user wants to see: summary.json's "events" and events/*.vtu.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/model/model.hpp"

namespace rockdd {

/// The damage pass of a step after which something first happened in the run.
struct RunEvent {
  std::string name;  // "first_damage" or "first_separation"
  long step = 0;     // the step that holds the pass
  int pass = 0;      // its damage pass, from 1
  double time = 0.0;
  std::int32_t damaged_elements = 0;  // w > 0 after the pass
  std::vector<double> parts;  // first_separation: the intact parts' areas (m^2), largest first
  std::string frame;          // its VTU file in the run folder, empty when none was written
};

/// An event with the model as that pass left it (displacements at the pass's solution).
struct EventState {
  RunEvent event;
  Model model;
};

}  // namespace rockdd

#pragma once
// A damage cascade of a quasi-static run followed with inertia (fracture.snap_back =
// "dynamic"): when the run turns dynamic, and the time step it goes on with.
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// True when pass `pass` of a step's damage iteration, having found new damage, calls for
/// inertia: snap_back = "dynamic" in a quasi-static analysis, and a re-solve after a damage
/// event found more (pass >= 2): damage spreading at held boundaries is a snap-back.
bool cascade_calls_for_inertia(const FractureSpec& fracture, Analysis analysis, int pass);

/// fracture.snap_back_dt, else a quarter of the shortest time a dilatational wave takes to
/// cross an element along its smallest height (plane stress or strain P-wave modulus, E0).
double snap_back_time_step(const Scene& scene, const Model& model);

}  // namespace rockdd

#pragma once
// The scene's loads as one nodal force vector at full magnitude.
#include <vector>

#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Nodal forces (2 per node, N over the thickness) of every [[load]] and of gravity, at full
/// magnitude: point forces shared by the point's nodes, curve forces and pressure spread by
/// length, body forces and gravity by element area. Pressure pushes along the inward normal.
std::vector<double> build_reference_loads(const Scene& scene, const Model& model);

/// Load factor at `time` of a run ending at `end_time`: a static analysis ramps the loads
/// linearly (n/N after step n of N); the other analyses apply them in full from the start.
double load_factor(Analysis analysis, double time, double end_time);

}  // namespace rockdd

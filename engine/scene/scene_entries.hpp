#pragma once
// Readers of the arrays of tables of a scene: [[material]], [[initial]], [[joint]],
// [[boundary]], [[load]], [[probe]]. Each validates every entry and the entries together.
#include <vector>

#include "engine/scene/scene.hpp"
#include "engine/scene/table_reader.hpp"

namespace rockdd {

/// [[material]]: at least one; one per body; poisson < 0.5 strictly in plane strain.
std::vector<MaterialSpec> read_materials(TableReader& root, PlaneKind plane);

/// [[initial]]: at most one per body.
std::vector<InitialSpec> read_initial(TableReader& root);

/// [[joint]]: `between` a pair of bodies, "crack" or "*"; each pair once.
std::vector<JointSpec> read_joints(TableReader& root);

/// [[boundary]]: fixed components and imposed velocities, each component constrained once.
std::vector<BoundarySpec> read_boundaries(TableReader& root);

/// [[load]]: exactly one of force, pressure, body + force_density each.
std::vector<LoadSpec> read_loads(TableReader& root);

/// [[probe]]: exactly one of at, on, body, line each; fields of that kind; unique names.
std::vector<ProbeSpec> read_probes(TableReader& root);

}  // namespace rockdd

#pragma once
// What happened before a Simulation was built, as its caller measured it, so that
// summary.json can account for every second of the process.
#include <optional>

#include "engine/mesh/mesh_cache.hpp"

namespace rockdd {

/// Seconds of each part of a run's set-up outside the Simulation, and the mesh's origin.
struct SetupReport {
  std::optional<double> startup;  // process start to the first engine call: loading, static init
  double scene = 0;               // reading and checking the scene file
  double meshing = 0;             // Gmsh, or reading the mesh cache
  double model = 0;               // blocks, materials, element strengths
  MeshCacheOutcome mesh_cache = MeshCacheOutcome::off;
};

}  // namespace rockdd

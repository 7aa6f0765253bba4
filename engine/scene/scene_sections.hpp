#pragma once
// Readers of the single tables of a scene: [scene], [time], [mesh], [output].
// Each takes the root table's reader and returns the validated spec.
#include <filesystem>

#include "engine/scene/scene.hpp"
#include "engine/scene/table_reader.hpp"

namespace rockdd {

/// [scene] (required): a Scene with name, analysis, plane, thickness and gravity set.
Scene read_scene_header(TableReader& root);

/// [time]: required unless `analysis` is static; a static scene without it runs one step
/// with dt = 1.
TimeSpec read_time(TableReader& root, Analysis analysis);

/// [mesh] (required): exactly one of geo, msh, shape; files resolved against `scene_dir`
/// and checked to be readable.
MeshSpec read_mesh(TableReader& root, const std::filesystem::path& scene_dir);

/// [fracture] (optional): the numerical devices of damage and fracture; their defaults are
/// recorded only when `has_damage` (a material can damage).
FractureSpec read_fracture(TableReader& root, bool has_damage, Analysis analysis);

/// [output] (optional): folder, frame interval and VTU fields.
SolverSpec read_solver(TableReader& root);
OutputSpec read_output(TableReader& root);
/// time.softening_probe names a history column of the scene's probes.
void check_softening_probe(TableReader& root, const Scene& scene);

}  // namespace rockdd

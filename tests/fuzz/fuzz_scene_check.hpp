#pragma once
// What `rockdd check` does with a scene before building the model, for the scene harnesses:
// read and validate it, then mesh it when it is a small built-in shape.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/mesh/gmsh_module.hpp"
#include "engine/mesh/mesh.hpp"
#include "engine/scene/mesh_budget.hpp"
#include "engine/scene/scene_reader.hpp"
#include "fuzz_input_error.hpp"

namespace rockdd::fuzz {

/// Largest estimated triangle count the harnesses mesh. Meshing is where the reader's limits
/// meet Gmsh (a 1e308 m rectangle once hung it), so accepted shapes are meshed; a cap keeps
/// each input to milliseconds, and a scene the reader accepts whose mesh is far larger than its
/// estimate (a hang or an RSS blow-up) is still found.
constexpr double kMostMeshedTriangles = 2000.0;

/// Parses `text` as the scene `file` with `overrides` applied; meshes a built-in shape whose
/// estimate is within kMostMeshedTriangles. Only InputErrors naming the file are accepted.
inline void check_scene(std::string_view text, const std::filesystem::path& file,
                        const std::vector<std::string>& overrides = {}) {
  expect_success_or_input_error(file.string(), [&] {
    const Scene scene = parse_scene(text, file, overrides);
    const auto triangles = estimated_triangles(scene.mesh);
    // In this process: a crash in Gmsh is a finding, not an InputError of the meshing process.
    if (triangles && *triangles <= kMostMeshedTriangles)
      build_mesh_in_this_process(scene.mesh, file);
  });
}

}  // namespace rockdd::fuzz

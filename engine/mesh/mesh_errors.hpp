#pragma once
#include "engine/common/number_format.hpp"
// How mesh problems are worded: the scene file and key they belong to, and points as text.
#include <string>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// Where a mesh comes from, for error messages: the scene file and its key ("mesh.geo").
struct MeshSource {
  std::string where;
  std::string key;
  /// Throws InputError(where, key, message).
  [[noreturn]] void fail(const std::string& message) const;
};

/// The scene key a mesh of `spec` comes from: "mesh.geo", "mesh.msh" or "mesh.shape".
std::string mesh_key(const MeshSpec& spec);

/// What a mesh of `spec` is called in messages: its file, or "the rectangle", "the disk".
std::string mesh_name(const MeshSpec& spec);

/// "(x,y)" with each coordinate in format_number form.
std::string point_text(double x, double y);

}  // namespace rockdd

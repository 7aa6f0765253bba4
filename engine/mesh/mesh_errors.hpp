#pragma once
#include "engine/common/number_format.hpp"
// How mesh problems are worded: the scene file and key they belong to, and points as text.
#include <string>

namespace rockdd {

/// Where a mesh comes from, for error messages: the scene file and its key ("mesh.geo").
struct MeshSource {
  std::string where;
  std::string key;
  /// Throws InputError(where, key, message).
  [[noreturn]] void fail(const std::string& message) const;
};

/// "(x,y)" with each coordinate in format_number form.
std::string point_text(double x, double y);

}  // namespace rockdd

#include "engine/mesh/mesh_errors.hpp"

#include <charconv>

#include "engine/common/errors.hpp"

namespace rockdd {

void MeshSource::fail(const std::string& message) const {
  throw InputError(where, key, message);
}

std::string point_text(double x, double y) {
  std::string text = "(";
  text += format_number(x);
  text += ',';
  text += format_number(y);
  text += ')';
  return text;
}

}  // namespace rockdd

#include "engine/mesh/mesh_errors.hpp"

#include <charconv>

#include "engine/errors.hpp"

namespace rockdd {

void MeshSource::fail(const std::string& message) const {
  throw InputError(where, key, message);
}

std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string point_text(double x, double y) {
  std::string text = "(";
  text += number_text(x);
  text += ',';
  text += number_text(y);
  text += ')';
  return text;
}

}  // namespace rockdd

#include "engine/output/number_format.hpp"

#include <charconv>

namespace rockdd {

std::string format_number(double value) {
  // The longest shortest-form double ("-2.2250738585072014e-308") has 24 chars, so
  // to_chars cannot run out of room here.
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace rockdd

#pragma once
// Text form of numbers in outputs and messages: the shortest form that reads back bit-exactly.
#include <charconv>
#include <string>

namespace rockdd {

/// Shortest decimal text that parses back to exactly `value` (std::to_chars).
inline std::string format_number(double value) {
  // The longest shortest-form double ("-2.2250738585072014e-308") has 24 characters.
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace rockdd

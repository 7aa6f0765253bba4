#pragma once
// Text form of numbers in CSV and JSON outputs: shortest form that reads back bit-exactly.
#include <string>

namespace rockdd {

/// Shortest decimal text that parses back to exactly `value` ("nan"/"inf" never expected).
std::string format_number(double value);

}  // namespace rockdd

#include "engine/scene/geometry_limits.hpp"

#include <cmath>

#include "engine/common/number_format.hpp"

namespace rockdd {

bool length_in_range(double length) {
  return std::isfinite(length) && length >= kShortestLength && length <= kLongestLength;
}

bool coordinate_in_range(double x) {
  return std::isfinite(x) && std::abs(x) <= kLongestLength;
}

bool keeps_precision(double farthest, double element_size) {
  return farthest <= kMostElementSizesFromOrigin * element_size;
}

std::string length_range_text() {
  return "in [" + format_number(kShortestLength) + ", " + format_number(kLongestLength) + "] m";
}

std::string precision_expectation() {
  return "coordinates within " + format_number(kMostElementSizesFromOrigin) +
         " element sizes of the origin (farther, rounding of the node positions swamps the "
         "strains)";
}

}  // namespace rockdd

#pragma once
// Element colouring: elements of one colour share no node, so a colour can scatter into
// nodal or matrix storage in parallel without races, and the order in which each entry
// receives its contributions (colour by colour) does not depend on the thread count.
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// Elements grouped by colour: colour c holds element[offset[c] .. offset[c+1]).
struct ElementColoring {
  std::vector<std::int32_t> offset;
  std::vector<std::int32_t> element;
  std::int32_t num_colors() const { return static_cast<std::int32_t>(offset.size()) - 1; }
};

/// Greedy colouring in element order (deterministic). Throws std::runtime_error if a node
/// touches more than 63 elements (no 2D triangle mesh of sane quality does).
ElementColoring color_elements(std::span<const std::int32_t> conn, std::int32_t num_nodes);

}  // namespace rockdd

#pragma once
// A node numbering that keeps mesh neighbours close in memory.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// Reverse Cuthill–McKee numbering of the graph whose edges are the triangles' sides:
/// returns the new number of each node. Each connected part starts from a pseudo-peripheral
/// node (George–Liu), parts in the order of their lowest old number. Every node must be on a
/// triangle. Small bandwidth keeps a node's neighbours, and so an element's nodes, nearby.
std::vector<std::int32_t> reverse_cuthill_mckee(std::size_t num_nodes,
                                                std::span<const std::int32_t> triangles);

}  // namespace rockdd

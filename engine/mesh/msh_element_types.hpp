#pragma once
// Gmsh's element types 1-31 as both .msh formats number them: how many nodes each lists and
// its dimension, for the checks that read a .msh before Gmsh does.
#include <array>
#include <cstdint>

namespace rockdd {

/// Nodes of an element of `type` (Gmsh's MElement::getInfoMSH for types 1-31), 0 if unknown.
inline int msh_nodes_of_type(std::int64_t type) {
  static constexpr std::array<int, 32> kNodes = {0,  2,  3,  4,  4, 8, 6,  5,  3,  6, 9,
                                                 10, 27, 18, 14, 1, 8, 20, 15, 13, 9, 10,
                                                 12, 15, 15, 21, 4, 5, 6,  20, 35, 56};
  return type > 0 && type < static_cast<std::int64_t>(kNodes.size()) ? kNodes[type] : 0;
}

/// Dimension of an element of `type` (point 0, lines 1, triangles and quadrangles 2, volumes
/// 3), -1 if unknown.
inline int msh_dimension_of_type(std::int64_t type) {
  static constexpr std::array<int, 32> kDimension = {-1, 1, 2, 2, 3, 3, 3, 3, 1, 2, 2,
                                                     3,  3, 3, 3, 0, 2, 3, 3, 3, 2, 2,
                                                     2,  2, 2, 2, 1, 1, 1, 3, 3, 3};
  return type > 0 && type < static_cast<std::int64_t>(kDimension.size()) ? kDimension[type] : -1;
}

}  // namespace rockdd

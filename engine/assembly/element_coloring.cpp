#include "engine/assembly/element_coloring.hpp"

#include <bit>
#include <stdexcept>
#include <string>

namespace rockdd {

ElementColoring color_elements(std::span<const std::int32_t> conn, std::int32_t num_nodes) {
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  std::vector<std::uint64_t> used(static_cast<std::size_t>(num_nodes), 0);
  std::vector<std::int8_t> color(static_cast<std::size_t>(num_elements));
  std::int32_t num_colors = 0;
  for (std::int32_t e = 0; e < num_elements; ++e) {
    const std::uint64_t taken = used[conn[3 * e]] | used[conn[3 * e + 1]] | used[conn[3 * e + 2]];
    const int c = std::countr_one(taken);
    if (c >= 63)
      throw std::runtime_error("element colouring: element " + std::to_string(e) +
                               " touches nodes shared by more than 63 elements");
    color[e] = static_cast<std::int8_t>(c);
    for (int k = 0; k < 3; ++k) used[conn[3 * e + k]] |= std::uint64_t{1} << c;
    num_colors = std::max(num_colors, c + 1);
  }
  ElementColoring coloring;
  coloring.offset.assign(static_cast<std::size_t>(num_colors) + 1, 0);
  for (std::int32_t e = 0; e < num_elements; ++e) ++coloring.offset[color[e] + 1];
  for (std::int32_t c = 0; c < num_colors; ++c) coloring.offset[c + 1] += coloring.offset[c];
  coloring.element.resize(static_cast<std::size_t>(num_elements));
  std::vector<std::int32_t> fill(coloring.offset.begin(), coloring.offset.end() - 1);
  for (std::int32_t e = 0; e < num_elements; ++e) coloring.element[fill[color[e]]++] = e;
  return coloring;
}

}  // namespace rockdd

#include "engine/assembly/element_coloring.hpp"

#include <bit>
#include <optional>
#include <stdexcept>
#include <string>

namespace rockdd {

namespace {

constexpr int kMaxColors = 63;

/// Greedy colouring of chunks of `chunk_size` elements, or nothing if it needs more than
/// kMaxColors colours (then `failed` is the first chunk left without one).
std::optional<ElementColoring> color_chunks(std::span<const std::int32_t> conn,
                                            std::int32_t num_nodes, std::int32_t chunk_size,
                                            std::int32_t& failed) {
  ElementColoring coloring;
  coloring.num_elements = static_cast<std::int32_t>(conn.size() / 3);
  coloring.chunk_size = chunk_size;
  const std::int32_t num_chunks = (coloring.num_elements + chunk_size - 1) / chunk_size;
  // used[n]: the colours of the chunks already coloured that touch node n.
  std::vector<std::uint64_t> used(static_cast<std::size_t>(num_nodes), 0);
  std::vector<std::int8_t> color(static_cast<std::size_t>(num_chunks));
  std::int32_t num_colors = 0;
  for (std::int32_t k = 0; k < num_chunks; ++k) {
    std::uint64_t taken = 0;
    const std::int32_t begin = coloring.chunk_begin(k), end = coloring.chunk_end(k);
    for (std::int32_t i = 3 * begin; i < 3 * end; ++i) taken |= used[conn[i]];
    const int c = std::countr_one(taken);
    if (c >= kMaxColors) {
      failed = k;
      return std::nullopt;
    }
    color[k] = static_cast<std::int8_t>(c);
    for (std::int32_t i = 3 * begin; i < 3 * end; ++i) used[conn[i]] |= std::uint64_t{1} << c;
    num_colors = std::max(num_colors, c + 1);
  }
  coloring.offset.assign(static_cast<std::size_t>(num_colors) + 1, 0);
  for (std::int32_t k = 0; k < num_chunks; ++k) ++coloring.offset[color[k] + 1];
  for (std::int32_t c = 0; c < num_colors; ++c) coloring.offset[c + 1] += coloring.offset[c];
  coloring.chunk.resize(static_cast<std::size_t>(num_chunks));
  std::vector<std::int32_t> fill(coloring.offset.begin(), coloring.offset.end() - 1);
  for (std::int32_t k = 0; k < num_chunks; ++k) coloring.chunk[fill[color[k]]++] = k;
  return coloring;
}

}  // namespace

std::int32_t coloring_chunk_size(std::int32_t num_elements) {
  return std::clamp(num_elements / 512, 1, 256);
}

ElementColoring color_elements(std::span<const std::int32_t> conn, std::int32_t num_nodes) {
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  for (std::int32_t size = coloring_chunk_size(num_elements);; size /= 2) {
    std::int32_t failed = 0;
    if (auto coloring = color_chunks(conn, num_nodes, size, failed)) return std::move(*coloring);
    if (size == 1)
      throw std::runtime_error("element colouring: element " + std::to_string(failed) +
                               " touches nodes shared by more than " + std::to_string(kMaxColors) +
                               " elements");
  }
}

}  // namespace rockdd

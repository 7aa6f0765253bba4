#pragma once
// Element colouring by chunks: elements are cut into runs of consecutive numbers (chunks),
// and chunks are coloured so that two chunks of one colour share no node. A colour can then
// scatter into nodal or matrix storage in parallel without races, and the order in which
// each entry receives its contributions (colour by colour, chunk by chunk, element by
// element) does not depend on the thread count. Chunks rather than single elements keep
// the elements a thread visits together neighbours in the mesh (finish_mesh sorts them by
// their lowest node in a bandwidth-reducing numbering), so they share their matrix columns
// and nodal entries in cache.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// Chunks of consecutive elements grouped by colour: colour c holds chunk[offset[c] ..
/// offset[c+1]), ascending; chunk k is elements [k chunk_size, (k + 1) chunk_size).
struct ElementColoring {
  std::int32_t num_elements = 0;
  std::int32_t chunk_size = 1;
  std::vector<std::int32_t> offset;
  std::vector<std::int32_t> chunk;
  std::int32_t num_colors() const { return static_cast<std::int32_t>(offset.size()) - 1; }
  std::int32_t chunk_begin(std::int32_t k) const { return k * chunk_size; }
  std::int32_t chunk_end(std::int32_t k) const {
    return std::min(num_elements, (k + 1) * chunk_size);
  }
};

/// The chunk size used for `num_elements` elements: a function of the mesh size only (never of
/// the thread count, so that results are too), about 512 chunks, at most 256 elements each.
std::int32_t coloring_chunk_size(std::int32_t num_elements);

/// Greedy colouring of the chunks in chunk order (deterministic). If the chunks need more
/// than 63 colours, smaller chunks are tried down to single elements; throws
/// std::runtime_error if even single elements need more (a node touching more than 63
/// elements: no 2D triangle mesh of sane quality does).
ElementColoring color_elements(std::span<const std::int32_t> conn, std::int32_t num_nodes);

}  // namespace rockdd

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

#include <tbb/parallel_for.h>

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

/// Calls body(e) for every element: colours in order, the chunks of one colour in parallel,
/// each chunk's elements in order. body may write to its element's nodes and their matrix
/// entries without synchronisation.
template <class ElementBody>
void for_each_element_by_color(const ElementColoring& coloring, const ElementBody& body) {
  // Tasks of at least ~512 elements: smaller ones cost more to schedule than to run.
  const std::int32_t grain = std::max(1, 512 / coloring.chunk_size);
  for (std::int32_t c = 0; c < coloring.num_colors(); ++c)
    tbb::parallel_for(
        tbb::blocked_range<std::int32_t>(coloring.offset[c], coloring.offset[c + 1], grain),
        [&](const tbb::blocked_range<std::int32_t>& range) {
          // A local copy of the body (its captures are references): they can then stay in
          // registers instead of being reloaded through `body` after every store.
          const ElementBody each = body;
          for (std::int32_t i = range.begin(); i != range.end(); ++i) {
            const std::int32_t k = coloring.chunk[i];
            const std::int32_t end = coloring.chunk_end(k);
            for (std::int32_t e = coloring.chunk_begin(k); e < end; ++e) each(e);
          }
        });
}

}  // namespace rockdd

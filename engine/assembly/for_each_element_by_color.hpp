#pragma once
// The parallel loop over elements by colour: what makes assembly race-free and its sums
// independent of the thread count (element_coloring.hpp).
#include <algorithm>
#include <cstdint>
#include <span>

#include <tbb/parallel_for.h>

#include "engine/assembly/element_coloring.hpp"

namespace rockdd {

/// Calls body(chunks) for consecutive runs of one colour's chunks (their numbers, in the
/// colouring's order; chunk_begin and chunk_end give their elements): colours in order, the
/// runs of one colour in parallel. body may write to its elements' nodes and their matrix
/// entries without synchronisation.
template <class ChunksBody>
void for_each_chunk_run_by_color(const ElementColoring& coloring, const ChunksBody& body) {
  // Tasks of at least ~512 elements: smaller ones cost more to schedule than to run.
  const std::int32_t grain = std::max(1, 512 / coloring.chunk_size);
  for (std::int32_t c = 0; c < coloring.num_colors(); ++c)
    tbb::parallel_for(
        tbb::blocked_range<std::int32_t>(coloring.offset[c], coloring.offset[c + 1], grain),
        [&](const tbb::blocked_range<std::int32_t>& range) {
          body(std::span<const std::int32_t>(coloring.chunk.data() + range.begin(),
                                             static_cast<std::size_t>(range.size())));
        });
}

/// Calls body(e) for every element: colours in order, the chunks of one colour in parallel,
/// each chunk's elements in order. body may write to its element's nodes and their matrix
/// entries without synchronisation.
template <class ElementBody>
void for_each_element_by_color(const ElementColoring& coloring, const ElementBody& body) {
  for_each_chunk_run_by_color(coloring, [&](std::span<const std::int32_t> chunks) {
    // A local copy of the body (its captures are references): they can then stay in registers
    // instead of being reloaded through `body` after every store.
    const ElementBody each = body;
    for (const std::int32_t k : chunks) {
      const std::int32_t end = coloring.chunk_end(k);
      for (std::int32_t e = coloring.chunk_begin(k); e < end; ++e) each(e);
    }
  });
}

}  // namespace rockdd

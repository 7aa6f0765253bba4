#pragma once
// Broad phase of contact detection: which boundary edges of different blocks may touch, from
// their bounding boxes sorted into a uniform grid, built and swept in parallel with oneTBB.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/contact/contact_detection.hpp"

namespace rockdd {

/// One flag per boundary edge: 1 where the edge's bounding box, grown by `margin`, overlaps
/// the grown box of an edge of another block that `rules` let touch it (either way round).
/// Grown boxes overlap when the edges are within 2 * margin of each other along both axes,
/// so a vertex within 2 * margin of an edge of another block lies on a flagged edge, and so
/// does that edge. The same flags whatever the thread count.
std::vector<std::uint8_t> flag_edges_near_other_blocks(const BlockBoundary& boundary,
                                                       std::span<const double> positions,
                                                       const ContactRules& rules, double margin);

/// The block pairs (a < b) that `rules` let touch with overlapping edge boxes grown by
/// `margin`: sorted and unique, so the same list whatever the thread count.
std::vector<std::array<std::int32_t, 2>> candidate_block_pairs(const BlockBoundary& boundary,
                                                               std::span<const double> positions,
                                                               const ContactRules& rules,
                                                               double margin);

}  // namespace rockdd

#pragma once
// Nested dissection of a planar mesh's node graph by the nodes' coordinates. A triangle mesh
// cut along a straight line has a separator as short as that line allows, which is what a
// graph partitioner searches for at far greater cost: each part is cut at the median node of
// its longer extent, the nodes of one side that touch the other become the separator, and
// both sides are cut again down to small leaves. CAMD then orders the leaves and separators
// by minimum degree, each separator after every part below it.
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// A symmetric graph in compressed rows, without self loops: the neighbours of vertex v are
/// index[offset[v]] .. index[offset[v + 1] - 1].
struct GraphView {
  std::span<const std::int32_t> offset;
  std::span<const std::int32_t> index;
  std::int32_t num_vertices() const { return static_cast<std::int32_t>(offset.size()) - 1; }
};

/// Parts of at most this many vertices are not cut again: CAMD orders them whole.
inline constexpr std::int32_t kDissectionLeafSize = 64;

/// Each vertex's level in the dissection: 0 inside a leaf, and for the vertices of a
/// separator one more than the highest level of the parts it separates. `x`, `y`: one
/// coordinate pair a vertex. Deterministic: ties in a coordinate go by vertex number.
std::vector<std::int32_t> coordinate_dissection_levels(
    const GraphView& graph, std::span<const double> x, std::span<const double> y,
    std::int32_t leaf_size = kDissectionLeafSize);

/// The elimination order of the vertices (order[k] is eliminated k-th): CAMD's minimum
/// degree, with the levels above as its constraint sets, so that every separator follows
/// the parts it separates.
std::vector<std::int32_t> coordinate_dissection_order(const GraphView& graph,
                                                      std::span<const double> x,
                                                      std::span<const double> y,
                                                      std::int32_t leaf_size = kDissectionLeafSize);

}  // namespace rockdd

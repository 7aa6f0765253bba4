#include "engine/solver/coordinate_dissection.hpp"

#include <camd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rockdd {
namespace {

/// The recursive cut. `mark_` tells, for the part being cut, which side of the cut line each
/// vertex lies on: fresh values per cut, so no array is cleared between cuts.
class Dissection {
 public:
  Dissection(const GraphView& graph, std::span<const double> x, std::span<const double> y,
             std::int32_t leaf_size)
      : graph_(graph),
        coordinate_{x, y},
        leaf_size_(std::max<std::int32_t>(leaf_size, 2)),
        level_(static_cast<std::size_t>(graph.num_vertices()), 0),
        mark_(static_cast<std::size_t>(graph.num_vertices()), -1),
        key_(static_cast<std::size_t>(graph.num_vertices())),
        local_(static_cast<std::size_t>(graph.num_vertices())) {
    // How far each vertex's neighbours reach along each direction: only a vertex whose reach
    // crosses the cut's median can touch the other side, so a cut scans the edges of those
    // alone (the same boundaries as a scan of every vertex, found in the same order).
    for (int d = 0; d < kDirections; ++d) {
      reach_[d].assign(static_cast<std::size_t>(graph.num_vertices()), 0.0);
      for (std::int32_t v = 0; v < graph.num_vertices(); ++v) {
        double far = 0.0;
        for (std::int32_t q = graph.offset[v]; q < graph.offset[v + 1]; ++q)
          far = std::max(far, std::abs(key_of(d, graph.index[q]) - key_of(d, v)));
        reach_[d][v] = far;
      }
    }
  }

  std::vector<std::int32_t> levels() && {
    std::vector<std::int32_t> all(static_cast<std::size_t>(graph_.num_vertices()));
    for (std::int32_t v = 0; v < graph_.num_vertices(); ++v) all[v] = v;
    dissect(std::move(all));
    return std::move(level_);
  }

 private:
  /// One way to cut a part: the vertices left on each side, and the separator between them.
  struct Cut {
    std::vector<std::int32_t> low, high, separator;
  };

  /// The fewest vertices that touch every edge between the two boundaries (König: as many as
  /// a maximum matching of those edges has). `high_mark`: the mark of the high side.
  std::vector<std::int32_t> minimum_cover(const std::vector<std::int32_t>& low,
                                          const std::vector<std::int32_t>& high,
                                          std::int64_t high_mark) {
    for (std::size_t i = 0; i < high.size(); ++i) local_[high[i]] = static_cast<std::int32_t>(i);
    // Edges from each low boundary vertex to the high side, in local numbers.
    std::vector<std::int32_t> start{0}, next;
    for (const std::int32_t v : low) {
      for (std::int32_t q = graph_.offset[v]; q < graph_.offset[v + 1]; ++q)
        if (const std::int32_t u = graph_.index[q]; mark_[u] == high_mark)
          next.push_back(local_[u]);
      start.push_back(static_cast<std::int32_t>(next.size()));
    }
    const auto nl = static_cast<std::int32_t>(low.size());
    const auto nh = static_cast<std::int32_t>(high.size());
    std::vector<std::int32_t> match_low(nl, -1), match_high(nh, -1), seen(nh, -1);
    // Augmenting paths from each low vertex (Kuhn), by an explicit stack.
    std::vector<std::int32_t> stack, edge_at;
    for (std::int32_t r = 0; r < nl; ++r) {
      stack.assign(1, r);
      edge_at.assign(1, start[r]);
      while (!stack.empty()) {
        const std::int32_t a = stack.back();
        std::int32_t& q = edge_at.back();
        if (q == start[a + 1]) {
          stack.pop_back();
          edge_at.pop_back();
          continue;
        }
        const std::int32_t b = next[q++];
        if (seen[b] == r) continue;
        seen[b] = r;
        if (match_high[b] < 0) {  // augment along the stack
          std::int32_t free_high = b;
          for (std::size_t k = stack.size(); k-- > 0;) {
            const std::int32_t low_vertex = stack[k];
            const std::int32_t previous = match_low[low_vertex];
            match_low[low_vertex] = free_high;
            match_high[free_high] = low_vertex;
            free_high = previous;
          }
          break;
        }
        stack.push_back(match_high[b]);
        edge_at.push_back(start[match_high[b]]);
      }
    }
    // König: Z = what alternating paths from unmatched low vertices reach; the cover is the
    // low vertices outside Z and the high vertices inside it.
    std::vector<std::uint8_t> low_reached(nl, 0), high_reached(nh, 0);
    std::vector<std::int32_t> queue;
    for (std::int32_t a = 0; a < nl; ++a)
      if (match_low[a] < 0) {
        low_reached[a] = 1;
        queue.push_back(a);
      }
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const std::int32_t a = queue[k];
      for (std::int32_t q = start[a]; q < start[a + 1]; ++q) {
        const std::int32_t b = next[q];
        if (high_reached[b]) continue;
        high_reached[b] = 1;
        const std::int32_t c = match_high[b];
        if (c >= 0 && !low_reached[c]) {
          low_reached[c] = 1;
          queue.push_back(c);
        }
      }
    }
    std::vector<std::int32_t> cover;
    for (std::int32_t a = 0; a < nl; ++a)
      if (!low_reached[a]) cover.push_back(low[a]);
    for (std::int32_t b = 0; b < nh; ++b)
      if (high_reached[b]) cover.push_back(high[b]);
    return cover;
  }

  /// Cuts `part` at its median node along `direction` (x, y, x + y, x - y), and takes as
  /// separator the fewest vertices that touch every edge across the cut.
  Cut cut_along(const std::vector<std::int32_t>& part, int direction) {
    for (const std::int32_t v : part) key_[v] = key_of(direction, v);
    const std::span<const double> c = key_;
    std::vector<std::int32_t> order = part;
    const auto middle = order.begin() + static_cast<std::ptrdiff_t>(order.size() / 2);
    std::nth_element(order.begin(), middle, order.end(), [&](std::int32_t a, std::int32_t b) {
      return c[a] < c[b] || (c[a] == c[b] && a < b);
    });
    const std::int64_t low_mark = next_mark_, high_mark = next_mark_ + 1;
    next_mark_ += 2;
    for (auto it = order.begin(); it != order.end(); ++it)
      mark_[*it] = it < middle ? low_mark : high_mark;
    Cut cut;
    cut.low.assign(order.begin(), middle);
    cut.high.assign(middle, order.end());
    std::vector<std::int32_t> low_boundary, high_boundary;
    const double median = c[*middle];
    const std::span<const double> reach = reach_[direction];
    for (const std::int32_t v : order) {
      const bool low = mark_[v] == low_mark;
      // Round-off in the reach is covered by a margin far above it: a vertex let through
      // needlessly only costs a scan of its edges.
      const double margin = 1e-9 * (std::abs(c[v]) + std::abs(median) + reach[v]);
      if (low ? c[v] + reach[v] < median - margin : c[v] - reach[v] > median + margin) continue;
      const std::int64_t other = low ? high_mark : low_mark;
      for (std::int32_t q = graph_.offset[v]; q < graph_.offset[v + 1]; ++q)
        if (mark_[graph_.index[q]] == other) {
          (low ? low_boundary : high_boundary).push_back(v);
          break;
        }
    }
    cut.separator = minimum_cover(low_boundary, high_boundary, high_mark);
    const std::int64_t separator_mark = next_mark_++;
    for (const std::int32_t v : cut.separator) mark_[v] = separator_mark;
    std::erase_if(cut.low, [&](std::int32_t v) { return mark_[v] == separator_mark; });
    std::erase_if(cut.high, [&](std::int32_t v) { return mark_[v] == separator_mark; });
    return cut;
  }

  /// Cuts `part` down to leaves; returns the highest level within it.
  std::int32_t dissect(std::vector<std::int32_t> part) {
    if (static_cast<std::int32_t>(part.size()) <= leaf_size_) return 0;  // levels stay 0
    // Four directions are tried and the shortest separator wins: on the disk mesh of 74k
    // dofs the diagonals took 5 % off the factor's flops that the axes alone left
    // (docs/performance.md, "Nested dissection by coordinates").
    Cut best = cut_along(part, 0);
    for (int direction = 1; direction < kDirections; ++direction) {
      Cut other = cut_along(part, direction);
      if (other.separator.size() < best.separator.size()) best = std::move(other);
    }
    part.clear();
    part.shrink_to_fit();
    const std::int32_t below =
        std::max(dissect(std::move(best.low)), dissect(std::move(best.high)));
    if (best.separator.empty()) return below;  // the sides were not connected
    for (const std::int32_t v : best.separator) level_[v] = below + 1;
    return below + 1;
  }

  /// Where vertex v lies along direction d.
  double key_of(int d, std::int32_t v) const {
    return kDirection[d][0] * coordinate_[0][v] + kDirection[d][1] * coordinate_[1][v];
  }

  static constexpr int kDirections = 4;
  static constexpr double kDirection[kDirections][2] = {
      {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, -1.0}};
  const GraphView& graph_;
  std::span<const double> coordinate_[2];
  std::vector<double> reach_[kDirections];
  std::int32_t leaf_size_;
  std::vector<std::int32_t> level_;
  std::vector<std::int64_t> mark_;
  std::vector<double> key_;
  std::vector<std::int32_t> local_;
  std::int64_t next_mark_ = 0;
};

void check_graph(const GraphView& graph, std::span<const double> x, std::span<const double> y) {
  if (graph.offset.empty()) throw std::invalid_argument("coordinate dissection: no vertex offsets");
  const auto n = static_cast<std::size_t>(graph.num_vertices());
  if (x.size() != n || y.size() != n)
    throw std::invalid_argument("coordinate dissection: " + std::to_string(x.size()) + " and " +
                                std::to_string(y.size()) + " coordinates for " + std::to_string(n) +
                                " vertices");
  // The median cuts order vertices by their coordinates, which a NaN would leave unordered.
  for (std::size_t v = 0; v < n; ++v)
    if (!std::isfinite(x[v]) || !std::isfinite(y[v]))
      throw std::invalid_argument("coordinate dissection: vertex " + std::to_string(v) +
                                  " has a coordinate that is not finite");
}

}  // namespace

std::vector<std::int32_t> coordinate_dissection_levels(const GraphView& graph,
                                                       std::span<const double> x,
                                                       std::span<const double> y,
                                                       std::int32_t leaf_size) {
  check_graph(graph, x, y);
  return Dissection(graph, x, y, leaf_size).levels();
}

std::vector<std::int32_t> coordinate_dissection_order(const GraphView& graph,
                                                      std::span<const double> x,
                                                      std::span<const double> y,
                                                      std::int32_t leaf_size) {
  const std::vector<std::int32_t> level = coordinate_dissection_levels(graph, x, y, leaf_size);
  const std::int32_t n = graph.num_vertices();
  std::vector<std::int32_t> order(static_cast<std::size_t>(n));
  if (graph.index.empty()) {  // no edge: nothing fills, any order will do
    for (std::int32_t v = 0; v < n; ++v) order[v] = v;
    return order;
  }
  const int status = camd_order(n, graph.offset.data(), graph.index.data(), order.data(), nullptr,
                                nullptr, level.data());
  if (status != CAMD_OK && status != CAMD_OK_BUT_JUMBLED)
    throw std::runtime_error("CAMD failed (status " + std::to_string(status) + ")");
  return order;
}

}  // namespace rockdd

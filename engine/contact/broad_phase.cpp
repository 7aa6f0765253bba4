#include "engine/contact/broad_phase.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

namespace rockdd {
namespace {

/// Edges per task in the parallel loops: the work per edge is a few dozen operations.
constexpr std::size_t kGrain = 2048;

/// Edges sorted by grid cell: the grown box of each edge, the cells it covers, and one key
/// (cell << 32 | edge) per covered cell, sorted so that each cell's edges form a run.
/// The arrays are not zeroed: parallel loops write every entry first, and so also take the
/// page faults in parallel.
struct EdgeGrid {
  std::unique_ptr<double[]> box;          // 4 per edge: x0, y0, x1, y1
  std::unique_ptr<std::int32_t[]> cells;  // 4 per edge: first column and row, last column and row
  std::unique_ptr<std::uint64_t[]> keys;
  std::size_t num_keys = 0;
  std::int64_t columns = 0, rows = 0;
};

/// Bounds of a set of boxes, for the parallel reduction.
struct Bounds {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};
};

/// Sorts keys (cell << 32 | edge), written edge by edge, by cell: a stable radix sort on the
/// cell bits (the edge bits are already in order), each pass counting and scattering fixed
/// chunks in parallel (with tbb::parallel_sort of the keys instead, the broad phase took 75
/// instead of 50 ms on one thread at 1e5 blocks).
void sort_by_cell(std::unique_ptr<std::uint64_t[]>& keys, std::size_t num_keys,
                  std::uint64_t num_cells) {
  constexpr std::size_t kChunk = 16384;
  int bits = 1;
  while (bits < 32 && (std::uint64_t{1} << bits) < num_cells) ++bits;
  const int passes = (bits + 10) / 11;
  const int width = (bits + passes - 1) / passes;
  const std::size_t buckets = std::size_t{1} << width;
  const std::size_t chunks = (num_keys + kChunk - 1) / kChunk;
  auto sorted = std::make_unique_for_overwrite<std::uint64_t[]>(num_keys);
  std::vector<std::size_t> offset(chunks * buckets);
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = 32 + pass * width;
    auto digit = [&](std::uint64_t key) {
      return static_cast<std::size_t>(key >> shift) & (buckets - 1);
    };
    std::fill(offset.begin(), offset.end(), 0);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      const std::size_t end = std::min(num_keys, (c + 1) * kChunk);
      for (std::size_t k = c * kChunk; k < end; ++k) ++offset[c * buckets + digit(keys[k])];
    });
    std::size_t total = 0;  // digit by digit, chunk by chunk: the chunks' order is kept
    for (std::size_t d = 0; d < buckets; ++d)
      for (std::size_t c = 0; c < chunks; ++c) {
        const std::size_t count = offset[c * buckets + d];
        offset[c * buckets + d] = total;
        total += count;
      }
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      const std::size_t end = std::min(num_keys, (c + 1) * kChunk);
      for (std::size_t k = c * kChunk; k < end; ++k)
        sorted[offset[c * buckets + digit(keys[k])]++] = keys[k];
    });
    keys.swap(sorted);
  }
}

EdgeGrid build_edge_grid(const BlockBoundary& boundary, std::span<const double> positions,
                         double margin) {
  const std::size_t num_edges = boundary.edge_block.size();
  EdgeGrid grid;
  grid.box = std::make_unique_for_overwrite<double[]>(4 * num_edges);
  grid.cells = std::make_unique_for_overwrite<std::int32_t[]>(4 * num_edges);
  const Bounds bounds = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, num_edges, kGrain), Bounds{},
      [&](const tbb::blocked_range<std::size_t>& range, Bounds b) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const std::size_t na = 2 * static_cast<std::size_t>(boundary.edge_nodes[2 * i]);
          const std::size_t nb = 2 * static_cast<std::size_t>(boundary.edge_nodes[2 * i + 1]);
          for (std::size_t d = 0; d < 2; ++d) {
            const double lo = std::min(positions[na + d], positions[nb + d]);
            const double hi = std::max(positions[na + d], positions[nb + d]);
            grid.box[4 * i + d] = lo;
            grid.box[4 * i + 2 + d] = hi;
            b.lo[d] = std::min(b.lo[d], lo);
            b.hi[d] = std::max(b.hi[d], hi);
          }
        }
        return b;
      },
      [](Bounds a, const Bounds& b) {
        for (int d = 0; d < 2; ++d) {
          a.lo[d] = std::min(a.lo[d], b.lo[d]);
          a.hi[d] = std::max(a.hi[d], b.hi[d]);
        }
        return a;
      });
  // The narrow phase's distances carry round-off of the coordinates' magnitude: a little more
  // margin keeps a vertex it finds exactly within reach inside the boxes.
  const double scale = std::max({std::abs(bounds.lo[0]), std::abs(bounds.lo[1]),
                                 std::abs(bounds.hi[0]), std::abs(bounds.hi[1])});
  const double grow = margin + 64 * DBL_EPSILON * scale;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_edges, kGrain), [&](auto range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      grid.box[4 * i] -= grow;
      grid.box[4 * i + 1] -= grow;
      grid.box[4 * i + 2] += grow;
      grid.box[4 * i + 3] += grow;
    }
  });

  // Cells about the median box size (from a strided sample: the same whatever the threads):
  // a typical box then covers 1 to 4 cells and a cell holds a few edges.
  std::vector<double> sample;
  const std::size_t stride = std::max<std::size_t>(1, num_edges / 1024);
  for (std::size_t i = 0; i < num_edges; i += stride)
    sample.push_back(
        std::max(grid.box[4 * i + 2] - grid.box[4 * i], grid.box[4 * i + 3] - grid.box[4 * i + 1]));
  std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
  double size = sample[sample.size() / 2];
  const double origin[2] = {bounds.lo[0] - grow, bounds.lo[1] - grow};
  const double extent[2] = {bounds.hi[0] - bounds.lo[0] + 2 * grow,
                            bounds.hi[1] - bounds.lo[1] + 2 * grow};
  if (!(size > 0)) size = std::max({extent[0], extent[1], 1.0});

  // Coarser cells while the cell ids overflow 32 bits or a few long edges would cover too many
  // cells (entries beyond 16 per edge): both only for scenes of very unequal edges.
  std::vector<std::size_t> offset(num_edges + 1, 0);
  for (;;) {
    const double inverse = 1.0 / size;
    const auto columns = static_cast<std::int64_t>(extent[0] * inverse) + 1;
    const auto rows = static_cast<std::int64_t>(extent[1] * inverse) + 1;
    if (static_cast<double>(columns) * static_cast<double>(rows) >= 0x1p32) {
      size *= 2;
      continue;
    }
    auto cell = [&](double x, int d, std::int64_t count) {
      return static_cast<std::int32_t>(std::clamp<std::int64_t>(
          static_cast<std::int64_t>((x - origin[d]) * inverse), 0, count - 1));
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_edges, kGrain), [&](auto range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        std::int32_t* c = &grid.cells[4 * i];
        c[0] = cell(grid.box[4 * i], 0, columns);
        c[1] = cell(grid.box[4 * i + 1], 1, rows);
        c[2] = cell(grid.box[4 * i + 2], 0, columns);
        c[3] = cell(grid.box[4 * i + 3], 1, rows);
        offset[i + 1] = static_cast<std::size_t>(c[2] - c[0] + 1) * (c[3] - c[1] + 1);
      }
    });
    std::inclusive_scan(offset.begin(), offset.end(), offset.begin());
    if (offset.back() <= 16 * num_edges + 1024) {
      grid.columns = columns;
      grid.rows = rows;
      break;
    }
    size *= 2;
  }

  grid.num_keys = offset.back();
  grid.keys = std::make_unique_for_overwrite<std::uint64_t[]>(grid.num_keys);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_edges, kGrain), [&](auto range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const std::int32_t* c = &grid.cells[4 * i];
      std::size_t k = offset[i];
      for (std::int64_t row = c[1]; row <= c[3]; ++row)
        for (std::int64_t column = c[0]; column <= c[2]; ++column)
          grid.keys[k++] = static_cast<std::uint64_t>(row * grid.columns + column) << 32 | i;
    }
  });
  sort_by_cell(grid.keys, grid.num_keys, static_cast<std::uint64_t>(grid.columns) * grid.rows);
  return grid;
}

/// Calls visit(i, j), i < j, once for every pair of edges of different blocks that the rules
/// let touch (either way round) whose grown boxes overlap. In parallel over the cells: visit
/// must be safe to call concurrently.
template <class Visit>
void for_each_overlap(const EdgeGrid& grid, const BlockBoundary& boundary,
                      const ContactRules& rules, Visit&& visit) {
  /// What the pair test reads of an edge, gathered once per cell instead of once per pair.
  struct Entry {
    double box[4];
    std::int32_t column, row, block;
    std::size_t edge, body;
  };
  const std::uint64_t* const keys = grid.keys.get();
  const std::size_t num_keys = grid.num_keys;
  const auto num_bodies = static_cast<std::size_t>(rules.num_bodies);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_keys, kGrain), [&](auto range) {
    std::vector<Entry> run;
    for (std::size_t start = range.begin(); start != range.end(); ++start) {
      const std::uint64_t cell = keys[start] >> 32;
      if (start > 0 && keys[start - 1] >> 32 == cell) continue;  // not the start of a run
      run.clear();
      for (std::size_t k = start; k < num_keys && keys[k] >> 32 == cell; ++k) {
        const auto i = static_cast<std::size_t>(keys[k] & 0xffffffffu);
        const std::int32_t block = boundary.edge_block[i];
        run.push_back(
            {{grid.box[4 * i], grid.box[4 * i + 1], grid.box[4 * i + 2], grid.box[4 * i + 3]},
             grid.cells[4 * i],
             grid.cells[4 * i + 1],
             block,
             i,
             static_cast<std::size_t>(rules.block_body[block])});
      }
      if (run.size() < 2) continue;
      const auto column = static_cast<std::int64_t>(cell) % grid.columns;
      const auto row = static_cast<std::int64_t>(cell) / grid.columns;
      for (std::size_t p = 0; p < run.size(); ++p) {
        const Entry& a = run[p];
        for (std::size_t q = p + 1; q < run.size(); ++q) {
          const Entry& b = run[q];
          if (a.block == b.block) continue;
          // A pair shares every cell of its boxes' intersection: it is visited only in the
          // cell of the intersection's lower-left corner.
          if (std::max(a.column, b.column) != column || std::max(a.row, b.row) != row) continue;
          if (a.box[0] > b.box[2] || b.box[0] > a.box[2] || a.box[1] > b.box[3] ||
              b.box[1] > a.box[3])
            continue;
          if (!rules.allowed[a.body * num_bodies + b.body] &&
              !rules.allowed[b.body * num_bodies + a.body])
            continue;
          visit(a.edge, b.edge);  // a.edge < b.edge: the run is in edge order
        }
      }
    }
  });
}

}  // namespace

std::vector<std::uint8_t> flag_edges_near_other_blocks(const BlockBoundary& boundary,
                                                       std::span<const double> positions,
                                                       const ContactRules& rules, double margin) {
  std::vector<std::uint8_t> flag(boundary.edge_block.size(), 0);
  if (flag.empty()) return flag;
  const EdgeGrid grid = build_edge_grid(boundary, positions, margin);
  // Concurrent visits only ever store 1: the flags are the same whatever the order.
  for_each_overlap(grid, boundary, rules, [&](std::size_t i, std::size_t j) {
    std::atomic_ref<std::uint8_t>(flag[i]).store(1, std::memory_order_relaxed);
    std::atomic_ref<std::uint8_t>(flag[j]).store(1, std::memory_order_relaxed);
  });
  return flag;
}

std::vector<std::array<std::int32_t, 2>> candidate_block_pairs(const BlockBoundary& boundary,
                                                               std::span<const double> positions,
                                                               const ContactRules& rules,
                                                               double margin) {
  using Pair = std::array<std::int32_t, 2>;
  if (boundary.edge_block.empty()) return {};
  const EdgeGrid grid = build_edge_grid(boundary, positions, margin);
  tbb::enumerable_thread_specific<std::vector<Pair>> found;
  for_each_overlap(grid, boundary, rules, [&](std::size_t i, std::size_t j) {
    const std::int32_t a = boundary.edge_block[i], b = boundary.edge_block[j];
    found.local().push_back({std::min(a, b), std::max(a, b)});
  });
  std::vector<Pair> pairs;
  for (const auto& list : found) pairs.insert(pairs.end(), list.begin(), list.end());
  tbb::parallel_sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace rockdd

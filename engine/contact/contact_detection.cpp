#include "engine/contact/contact_detection.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <nanoflann.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>

#include "engine/contact/broad_phase.hpp"
#include "engine/model/edge_adjacency.hpp"
#include "kernels/contact_geometry.hpp"

namespace rockdd {
namespace {

/// nanoflann adaptor over a contiguous copy of the searched vertices' positions (2 per
/// vertex): the tree's build and search read them without going through the node ids.
struct VertexCloud {
  std::span<const double> xy;
  std::size_t kdtree_get_point_count() const { return xy.size() / 2; }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return xy[2 * i + dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using VertexTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, VertexCloud>,
                                        VertexCloud, 2, std::size_t>;

/// Normals must be opposed by more than this cosine: a vertex of a flat face against a face
/// at right angles (facing = 0 up to round-off) is the corner of the other block passing by,
/// not a contact, and would otherwise catch it with the full distance as penetration.
constexpr double kFacingMargin = 0.05;

/// A vertex within this fraction of an edge's length from one of its ends sits on that corner:
/// the direction between the two is round-off and deformation, not an approach direction,
/// so it cannot tell which of the corner's two faces the vertex would enter through.
constexpr double kCornerFraction = 1e-3;

/// A face of the vertex's block and a face of the other block leaving a shared corner lie on
/// each other (the two sides of one crack) when their directions agree within this cosine
/// (about 10 degrees).
constexpr double kOverlappingFaces = 0.985;

/// How a vertex meets an edge, in the reduction's order of preference.
enum class Meeting : std::uint8_t {
  shared_face,  // on the edge's corner, one of its own faces along the edge: a split crack face
  on_corner,    // on the edge's corner with no face along it: no contact with this block
  inside,       // projects inside the edge
  near_corner,  // projects past an end: vertex-vertex, the face it is least behind wins
};

/// A candidate with what the reduction needs: the block pair, the gap and how they meet.
struct Found {
  std::int32_t vertex, edge, edge_block;  // vertex: index into BlockBoundary's vertices
  double gap;
  Meeting meeting;
};

/// Indices i with keep[i] != 0, ascending: counted per chunk, then written in parallel.
std::vector<std::int32_t> flagged_indices(std::span<const std::uint8_t> keep) {
  constexpr std::size_t kChunk = 16384;
  const std::size_t chunks = (keep.size() + kChunk - 1) / kChunk;
  std::vector<std::size_t> offset(chunks + 1, 0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    const std::size_t end = std::min(keep.size(), (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < end; ++i) offset[c + 1] += keep[i] != 0;
  });
  std::inclusive_scan(offset.begin(), offset.end(), offset.begin());
  std::vector<std::int32_t> out(offset.back());
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    const std::size_t end = std::min(keep.size(), (c + 1) * kChunk);
    std::size_t k = offset[c];
    for (std::size_t i = c * kChunk; i < end; ++i)
      if (keep[i]) out[k++] = static_cast<std::int32_t>(i);
  });
  return out;
}

/// Unit outward normals (2 each) of the boundary edges that touch a searched vertex, and of
/// the searched vertices; the others are left at zero. The edges of searched vertex v are
/// incident[start[v] .. start[v + 1]), in edge order.
struct Normals {
  std::vector<double> edge, vertex;
  std::vector<std::int32_t> start, incident;
};

/// The outward normal of a vertex is the mean of its boundary edges' normals. A vertex may
/// only touch a face that it faces (normals opposed): otherwise a block that has sunk by the
/// penalty penetration would catch the other block's surface vertices on its side faces as it
/// slides past them. Each vertex adds its edges' normals in edge order, as a serial pass over
/// the edges would, so the bits do not depend on the threads: its edges are counted, scattered
/// in any order, and each vertex's list is sorted.
Normals outward_normals(const BlockBoundary& boundary, std::span<const double> positions,
                        std::span<const std::int32_t> edge_vertex,
                        std::span<const std::uint8_t> searched) {
  const std::size_t num_edges = boundary.edge_block.size();
  const std::size_t num_vertices = boundary.vertices.size();
  Normals normals{
      std::vector<double>(2 * num_edges, 0.0), std::vector<double>(2 * num_vertices, 0.0), {}, {}};
  std::vector<std::int32_t> start(num_vertices + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_edges, 2048), [&](auto range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const std::int32_t va = edge_vertex[2 * i], vb = edge_vertex[2 * i + 1];
      if (!searched[va] && !searched[vb]) continue;
      const std::int32_t na = boundary.edge_nodes[2 * i], nb = boundary.edge_nodes[2 * i + 1];
      const double ex = positions[2 * nb] - positions[2 * na],
                   ey = positions[2 * nb + 1] - positions[2 * na + 1];
      const double length = std::hypot(ex, ey);
      normals.edge[2 * i] = ey / length;
      normals.edge[2 * i + 1] = -ex / length;
      for (const std::int32_t v : {va, vb})
        if (searched[v])
          std::atomic_ref<std::int32_t>(start[v + 1]).fetch_add(1, std::memory_order_relaxed);
    }
  });
  std::inclusive_scan(start.begin(), start.end(), start.begin());
  std::vector<std::int32_t> incident(static_cast<std::size_t>(start.back()));
  std::vector<std::int32_t> cursor(start.begin(), start.end() - 1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, 2 * num_edges, 4096), [&](auto range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k)
      if (searched[edge_vertex[k]])
        incident[std::atomic_ref<std::int32_t>(cursor[edge_vertex[k]])
                     .fetch_add(1, std::memory_order_relaxed)] = static_cast<std::int32_t>(k / 2);
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices, 4096), [&](auto range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      const auto first = incident.begin() + start[v], last = incident.begin() + start[v + 1];
      std::sort(first, last);
      for (auto e = first; e != last; ++e) {
        normals.vertex[2 * v] += normals.edge[2 * *e];
        normals.vertex[2 * v + 1] += normals.edge[2 * *e + 1];
      }
    }
  });
  normals.start = std::move(start);
  normals.incident = std::move(incident);
  return normals;
}

/// Whether one of vertex v's own boundary edges leaves v along `direction` (unit): the
/// vertex's face lies on the other block's face that leaves the shared corner that way.
bool has_face_along(std::size_t v, const double direction[2], const Normals& normals,
                    std::span<const std::int32_t> edge_vertex) {
  for (std::int32_t k = normals.start[v]; k < normals.start[v + 1]; ++k) {
    const auto e = static_cast<std::size_t>(normals.incident[k]);
    // The edge's tangent is the normal turned back by 90 degrees; it leaves v forwards when
    // v is the edge's first end.
    const double sign = edge_vertex[2 * e] == static_cast<std::int32_t>(v) ? 1.0 : -1.0;
    const double tx = -normals.edge[2 * e + 1] * sign, ty = normals.edge[2 * e] * sign;
    if (tx * direction[0] + ty * direction[1] > kOverlappingFaces) return true;
  }
  return false;
}

}  // namespace

BlockBoundary extract_block_boundary(const Model& model) {
  return extract_block_boundary(model, build_edge_adjacency(model.conn, "model"));
}

BlockBoundary extract_block_boundary(const Model& model, const EdgeAdjacency& adjacency) {
  BlockBoundary boundary;
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t other = adjacency.neighbor[3 * e + k];
      if (other >= 0 && model.element_block[other] == model.element_block[e]) continue;
      boundary.edge_nodes.push_back(model.conn[3 * e + k]);
      boundary.edge_nodes.push_back(model.conn[3 * e + (k + 1) % 3]);
      boundary.edge_element.push_back(e);
      boundary.edge_block.push_back(model.element_block[e]);
    }
  boundary.vertices = boundary.edge_nodes;
  std::sort(boundary.vertices.begin(), boundary.vertices.end());
  boundary.vertices.erase(std::unique(boundary.vertices.begin(), boundary.vertices.end()),
                          boundary.vertices.end());
  boundary.vertex_block.resize(boundary.vertices.size());
  for (std::size_t i = 0; i < boundary.vertices.size(); ++i)
    boundary.vertex_block[i] = model.node_block[boundary.vertices[i]];
  return boundary;
}

std::vector<ContactCandidate> detect_contacts(const BlockBoundary& boundary,
                                              std::span<const double> positions,
                                              const ContactRules& rules, double reach,
                                              double inflation) {
  const std::size_t num_edges = boundary.edge_block.size();
  if (num_edges == 0) return {};
  const std::size_t num_vertices = boundary.vertices.size();

  // Broad phase: edge boxes grown by half the reach overlap when the edges are within reach,
  // and by the step's largest displacement on each side since both blocks may move. A vertex
  // within reach of an edge of another block lies on edges of its own block, so that edge and
  // the vertex's edges are all flagged: only flagged edges are searched, and the tree holds
  // only their vertices (in a pile with 5 % of the edges flagged, 25 % less time than a tree
  // over all vertices).
  const std::vector<std::uint8_t> near =
      flag_edges_near_other_blocks(boundary, positions, rules, 0.5 * reach + inflation);
  const std::vector<std::int32_t> edges = flagged_indices(near);
  if (edges.empty()) return {};

  // Boundary vertex of each edge end, through a dense node -> vertex map (no binary search).
  std::vector<std::int32_t> vertex_of_node(static_cast<std::size_t>(boundary.vertices.back()) + 1);
  tbb::parallel_for(std::size_t{0}, num_vertices, [&](std::size_t v) {
    vertex_of_node[boundary.vertices[v]] = static_cast<std::int32_t>(v);
  });
  std::vector<std::int32_t> edge_vertex(2 * num_edges);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, 2 * num_edges, 4096), [&](auto range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k)
      edge_vertex[k] = vertex_of_node[boundary.edge_nodes[k]];
  });

  // The searched vertices (those of flagged edges) and a contiguous copy of their positions.
  std::vector<std::uint8_t> searched(num_vertices, 0);
  tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t k) {
    for (int end = 0; end < 2; ++end)
      std::atomic_ref<std::uint8_t>(
          searched[edge_vertex[2 * static_cast<std::size_t>(edges[k]) + end]])
          .store(1, std::memory_order_relaxed);
  });
  const std::vector<std::int32_t> tree_vertex = flagged_indices(searched);
  std::vector<double> tree_xy(2 * tree_vertex.size());
  tbb::parallel_for(std::size_t{0}, tree_vertex.size(), [&](std::size_t t) {
    const auto n = static_cast<std::size_t>(boundary.vertices[tree_vertex[t]]);
    tree_xy[2 * t] = positions[2 * n];
    tree_xy[2 * t + 1] = positions[2 * n + 1];
  });

  // nanoflann builds its tree on one thread (8 % of the work at 1e5 blocks): the other
  // threads compute the normals meanwhile.
  const VertexCloud cloud{tree_xy};
  std::optional<VertexTree> tree;
  Normals normals;
  tbb::parallel_invoke(
      [&] { tree.emplace(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)); },
      [&] { normals = outward_normals(boundary, positions, edge_vertex, searched); });

  // Narrow phase per flagged edge, in parallel over fixed chunks of edges, each writing its
  // own list: small lists that the allocator reuses from call to call, where one growing list
  // per thread was page-faulted in afresh each time. Two cheap tests come before the kernel
  // and its two square roots: the facing test is the kernel's own product (the kernel's
  // normal is the edge normal above, to the bit), and the distance to the edge's line.
  constexpr std::size_t kChunk = 256;
  std::vector<std::vector<Found>> found((edges.size() + kChunk - 1) / kChunk);
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t chunk) {
    std::vector<Found>& local = found[chunk];
    const std::size_t end = std::min(edges.size(), (chunk + 1) * kChunk);
    std::vector<std::pair<std::size_t, double>> hits;
    for (std::size_t k = chunk * kChunk; k < end; ++k) {
      const auto i = static_cast<std::size_t>(edges[k]);
      const std::int32_t na = boundary.edge_nodes[2 * i], nb = boundary.edge_nodes[2 * i + 1];
      const double a[2] = {positions[2 * na], positions[2 * na + 1]};
      const double b[2] = {positions[2 * nb], positions[2 * nb + 1]};
      const double e[2] = {b[0] - a[0], b[1] - a[1]};
      const double centre[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
      const double length = std::hypot(e[0], e[1]);
      const double radius = 0.5 * length + reach;
      // A vertex farther than reach from the edge's line is farther from the edge: rejected
      // before the kernel, with room for the round-off of both computations.
      const double off_line_limit =
          (reach + 1e-9 * (reach + length) +
           1e-12 * (std::abs(a[0]) + std::abs(a[1]) + std::abs(b[0]) + std::abs(b[1]))) *
          length;
      hits.clear();
      nanoflann::SearchParams params;
      params.sorted = false;
      tree->radiusSearch(centre, radius * radius, hits, params);  // squared radius for L2
      const std::int32_t edge_block = boundary.edge_block[i];
      const std::int32_t edge_body = rules.block_body[edge_block];
      const double normal[2] = {normals.edge[2 * i], normals.edge[2 * i + 1]};
      for (const auto& [t, squared] : hits) {
        const auto index = static_cast<std::size_t>(tree_vertex[t]);
        const std::int32_t vertex_block = boundary.vertex_block[index];
        if (vertex_block == edge_block) continue;
        if (!rules.inert.empty() && (rules.inert[vertex_block] || rules.inert[edge_block]))
          continue;
        const double facing =
            normal[0] * normals.vertex[2 * index] + normal[1] * normals.vertex[2 * index + 1];
        if (!(facing < -kFacingMargin)) continue;
        const std::int32_t vertex_body = rules.block_body[vertex_block];
        if (!rules.allowed[static_cast<std::size_t>(vertex_body) * rules.num_bodies + edge_body])
          continue;
        const double p[2] = {tree_xy[2 * t], tree_xy[2 * t + 1]};
        if (std::abs((p[0] - a[0]) * e[1] - (p[1] - a[1]) * e[0]) > off_line_limit) continue;
        const kernels::VertexEdge c = kernels::vertex_edge(p, a, b);
        if (c.distance > reach) continue;
        Meeting meeting = Meeting::inside;
        const double corner = kCornerFraction * c.length;
        if (c.xi * c.length <= corner || (1.0 - c.xi) * c.length <= corner) {
          meeting = Meeting::near_corner;
          // A vertex on a corner (a copy of a split node) touches the corner's edge only if
          // one of its own faces lies on it. Otherwise every copy of a node where several
          // fractured elements meet would press on the faces of all the others, with a
          // normal that round-off picks, and a thin element's far edge would see it as
          // deeply inside.
          const double to_corner = c.xi < 0.5 ? std::hypot(p[0] - a[0], p[1] - a[1])
                                              : std::hypot(p[0] - b[0], p[1] - b[1]);
          if (to_corner <= corner) {
            const double sign = c.xi < 0.5 ? 1.0 : -1.0;  // the edge leaves the corner
            const double direction[2] = {sign * c.tangent[0], sign * c.tangent[1]};
            meeting = has_face_along(index, direction, normals, edge_vertex) ? Meeting::shared_face
                                                                             : Meeting::on_corner;
          }
        }
        local.push_back({static_cast<std::int32_t>(index), static_cast<std::int32_t>(i), edge_block,
                         c.gap, meeting});
      }
    }
  });

  // Group the found pairs by vertex: counted, then scattered in any order (each group is
  // sorted below), all in parallel. The grouped copy is not zeroed first: the scatter writes
  // every entry.
  auto for_each_found = [&](auto&& f) {
    tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t chunk) {
      for (const Found& x : found[chunk]) f(x);
    });
  };
  std::vector<std::int32_t> group_start(num_vertices + 1, 0);
  for_each_found([&](const Found& x) {
    std::atomic_ref<std::int32_t>(group_start[x.vertex + 1])
        .fetch_add(1, std::memory_order_relaxed);
  });
  std::inclusive_scan(group_start.begin(), group_start.end(), group_start.begin());
  const auto grouped = std::make_unique_for_overwrite<Found[]>(group_start.back());
  {
    std::vector<std::int32_t> cursor(group_start.begin(), group_start.end() - 1);
    for_each_found([&](const Found& x) {
      grouped[std::atomic_ref<std::int32_t>(cursor[x.vertex])
                  .fetch_add(1, std::memory_order_relaxed)] = x;
    });
  }

  // Keep, for each vertex and each other block: the edges its own faces lie on when it sits
  // on their corner (both sides of a crack, where a split node's copies meet), and nothing
  // else of that block; otherwise the edge it projects inside of, if any: on a flat face the
  // neighbouring edges' extensions give the same gap, and pairing the vertex with one of
  // them would make it a vertex-vertex contact a whole edge away. Among those (or among the
  // rest, at a corner), the largest gap wins (ties: lower edge index): near a convex corner
  // the vertex penetrates only if it is behind both faces, and then the face it is least
  // behind is the one it came through. Both sorts are total orders (a vertex meets an edge
  // once), so the list does not depend on the threads. The kept pairs move to the front of
  // their group.
  std::vector<std::int32_t> kept_start(num_vertices + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices, 1024), [&](auto range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      Found* const first = grouped.get() + group_start[v];
      Found* const last = grouped.get() + group_start[v + 1];
      std::sort(first, last, [](const Found& x, const Found& y) {
        if (x.edge_block != y.edge_block) return x.edge_block < y.edge_block;
        if (x.meeting != y.meeting) return x.meeting < y.meeting;
        if (x.gap != y.gap) return x.gap > y.gap;
        return x.edge < y.edge;
      });
      Found* kept = first;
      std::int32_t block = -1;  // the block of the last group
      for (Found* x = first; x != last; ++x) {
        const bool another_shared_face = x->edge_block == block &&
                                         x->meeting == Meeting::shared_face &&
                                         (kept - 1)->meeting == Meeting::shared_face;
        if (x->edge_block == block && !another_shared_face) continue;
        block = x->edge_block;
        if (x->meeting != Meeting::on_corner) *kept++ = *x;
      }
      std::sort(first, kept, [](const Found& x, const Found& y) { return x.edge < y.edge; });
      kept_start[v + 1] = static_cast<std::int32_t>(kept - first);
    }
  });
  std::inclusive_scan(kept_start.begin(), kept_start.end(), kept_start.begin());
  std::vector<ContactCandidate> out(static_cast<std::size_t>(kept_start.back()));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices, 4096), [&](auto range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v)
      for (std::int32_t k = 0; k < kept_start[v + 1] - kept_start[v]; ++k)
        out[kept_start[v] + k] = {boundary.vertices[v], grouped[group_start[v] + k].edge};
  });
  return out;
}

}  // namespace rockdd

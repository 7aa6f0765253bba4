#include "engine/contact/contact_detection.hpp"

#include <tbb/parallel_for.h>
#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>

#include "engine/model/edge_adjacency.hpp"
#include "kernels/contact_geometry.hpp"

namespace rockdd {
namespace {

/// nanoflann adaptor over the boundary vertices' current positions.
struct VertexCloud {
  const BlockBoundary* boundary;
  std::span<const double> positions;
  std::size_t kdtree_get_point_count() const { return boundary->vertices.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return positions[2 * static_cast<std::size_t>(boundary->vertices[i]) + dim];
  }
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

/// A candidate with what the reduction needs: the block pair and the distance.
struct Found {
  std::int32_t vertex, edge, edge_block;
  double gap;
  bool interior;  // the vertex projects inside the edge, not past one of its ends
};

}  // namespace

BlockBoundary extract_block_boundary(const Model& model) {
  const EdgeAdjacency adjacency = build_edge_adjacency(model.conn, "model");
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
                                              const ContactRules& rules, double reach) {
  const std::size_t num_edges = boundary.edge_block.size();
  if (num_edges == 0) return {};
  VertexCloud cloud{&boundary, positions};
  VertexTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();

  // Outward normal of each boundary vertex: the mean of its boundary edges' normals. A vertex
  // may only touch a face that it faces (normals opposed): otherwise a block that has sunk by
  // the penalty penetration would catch the other block's surface vertices on its side faces
  // as it slides past them.
  std::vector<double> vertex_normal(2 * boundary.vertices.size(), 0.0);
  for (std::size_t i = 0; i < num_edges; ++i) {
    const std::int32_t na = boundary.edge_nodes[2 * i], nb = boundary.edge_nodes[2 * i + 1];
    const double ex = positions[2 * nb] - positions[2 * na],
                 ey = positions[2 * nb + 1] - positions[2 * na + 1];
    const double length = std::hypot(ex, ey);
    for (const std::int32_t n : {na, nb}) {
      const auto v = std::lower_bound(boundary.vertices.begin(), boundary.vertices.end(), n) -
                     boundary.vertices.begin();
      vertex_normal[2 * v] += ey / length;
      vertex_normal[2 * v + 1] -= ex / length;
    }
  }

  // Broad and narrow phase per edge, in parallel; each edge writes only its own list.
  std::vector<std::vector<Found>> per_edge(num_edges);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_edges, 256), [&](auto range) {
    std::vector<std::pair<std::size_t, double>> hits;
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const std::int32_t na = boundary.edge_nodes[2 * i], nb = boundary.edge_nodes[2 * i + 1];
      const double a[2] = {positions[2 * na], positions[2 * na + 1]};
      const double b[2] = {positions[2 * nb], positions[2 * nb + 1]};
      const double centre[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
      const double radius = 0.5 * std::hypot(b[0] - a[0], b[1] - a[1]) + reach;
      hits.clear();
      nanoflann::SearchParams params;
      params.sorted = false;
      tree.radiusSearch(centre, radius * radius, hits, params);  // squared radius for L2
      const std::int32_t edge_block = boundary.edge_block[i];
      const std::int32_t edge_body = rules.block_body[edge_block];
      for (const auto& [index, squared] : hits) {
        const std::int32_t vertex_block = boundary.vertex_block[index];
        if (vertex_block == edge_block) continue;
        const std::int32_t vertex_body = rules.block_body[vertex_block];
        if (!rules.allowed[static_cast<std::size_t>(vertex_body * rules.num_bodies + edge_body)])
          continue;
        const std::int32_t v = boundary.vertices[index];
        const double p[2] = {positions[2 * v], positions[2 * v + 1]};
        const kernels::VertexEdge c = kernels::vertex_edge(p, a, b);
        const double facing =
            c.normal[0] * vertex_normal[2 * index] + c.normal[1] * vertex_normal[2 * index + 1];
        if (c.distance <= reach && facing < -kFacingMargin)
          per_edge[i].push_back(
              {v, static_cast<std::int32_t>(i), edge_block, c.gap, c.xi > 0.0 && c.xi < 1.0});
      }
    }
  });

  // Keep, for each vertex and each other block, the edge it projects inside of, if any: on a
  // flat face the neighbouring edges' extensions give the same gap, and pairing the vertex
  // with one of them would make it a vertex-vertex contact a whole edge away. Among those
  // (or among the rest, at a corner), the largest gap wins (ties: lower edge index): near a
  // convex corner the vertex penetrates only if it is behind both faces, and then the face
  // it is least behind is the one it came through.
  std::vector<Found> all;
  for (const auto& list : per_edge) all.insert(all.end(), list.begin(), list.end());
  std::sort(all.begin(), all.end(), [](const Found& x, const Found& y) {
    if (x.vertex != y.vertex) return x.vertex < y.vertex;
    if (x.edge_block != y.edge_block) return x.edge_block < y.edge_block;
    if (x.interior != y.interior) return x.interior;
    if (x.gap != y.gap) return x.gap > y.gap;
    return x.edge < y.edge;
  });
  std::vector<ContactCandidate> out;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (i == 0 || all[i].vertex != all[i - 1].vertex || all[i].edge_block != all[i - 1].edge_block)
      out.push_back({all[i].vertex, all[i].edge});
  std::sort(out.begin(), out.end(), [](const ContactCandidate& x, const ContactCandidate& y) {
    return x.vertex != y.vertex ? x.vertex < y.vertex : x.edge < y.edge;
  });
  return out;
}

}  // namespace rockdd

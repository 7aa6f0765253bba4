#include "engine/mesh/finish_mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "engine/mesh/node_ordering.hpp"

namespace rockdd {

namespace {

std::vector<char> nodes_on_triangles(std::size_t num_nodes,
                                     const std::vector<std::int32_t>& triangles) {
  std::vector<char> used(num_nodes, 0);
  for (const std::int32_t n : triangles) used[n] = 1;
  return used;
}

std::string node_text(const std::vector<double>& xy, std::int32_t n) {
  return point_text(xy[2 * n], xy[2 * n + 1]);
}

/// A node of a boundary condition that no element carries would have no stiffness.
void require_on_triangles(const Mesh& mesh, const std::vector<char>& used,
                          const MeshSource& source) {
  for (const auto& [name, edges] : mesh.curves)
    for (const auto& edge : edges)
      for (const std::int32_t n : edge)
        if (!used[n])
          source.fail("physical curve '" + name + "' has nodes on no triangle (node at " +
                      node_text(mesh.xy, n) + ")");
  for (const auto& [name, nodes] : mesh.points)
    for (const std::int32_t n : nodes)
      if (!used[n])
        source.fail("physical point '" + name + "' is on no triangle (node at " +
                    node_text(mesh.xy, n) + ")");
}

/// Twice the signed area of triangle e: positive when counter-clockwise.
double twice_signed_area(const std::vector<double>& xy, const std::int32_t* t) {
  const double ax = xy[2 * t[0]], ay = xy[2 * t[0] + 1];
  return (xy[2 * t[1]] - ax) * (xy[2 * t[2] + 1] - ay) -
         (xy[2 * t[2]] - ax) * (xy[2 * t[1] + 1] - ay);
}

/// Gmsh orients triangles along each surface's normal, which may point down.
void turn_counter_clockwise(const std::vector<double>& xy, std::vector<std::int32_t>& triangles) {
  for (std::size_t e = 0; e < triangles.size(); e += 3)
    if (twice_signed_area(xy, &triangles[e]) < 0.0) std::swap(triangles[e + 1], triangles[e + 2]);
}

/// New number of every raw node: the nodes on triangles in reverse Cuthill–McKee order,
/// -1 for the others.
std::vector<std::int32_t> new_node_numbers(const std::vector<char>& used,
                                           const std::vector<std::int32_t>& triangles) {
  std::vector<std::int32_t> compact(used.size(), -1);
  std::int32_t count = 0;
  for (std::size_t n = 0; n < used.size(); ++n)
    if (used[n]) compact[n] = count++;
  std::vector<std::int32_t> compact_triangles(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) compact_triangles[i] = compact[triangles[i]];
  const std::vector<std::int32_t> ordered =
      reverse_cuthill_mckee(static_cast<std::size_t>(count), compact_triangles);
  for (auto& n : compact)
    if (n >= 0) n = ordered[n];
  return compact;
}

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

/// The curve's edges in new numbers, each along a triangle side in that triangle's direction.
std::vector<std::array<std::int32_t, 2>> curve_edges(
    const std::string& name, const std::vector<std::array<std::int32_t, 2>>& raw_edges,
    const std::vector<std::int32_t>& number, const std::unordered_set<std::uint64_t>& sides,
    const Mesh& finished, const MeshSource& source) {
  std::vector<std::array<std::int32_t, 2>> edges;
  std::unordered_set<std::uint64_t> seen;
  for (const auto& raw : raw_edges) {
    std::int32_t a = number[raw[0]], b = number[raw[1]];
    if (!sides.count(edge_key(a, b))) std::swap(a, b);
    if (!sides.count(edge_key(a, b)))
      source.fail("physical curve '" + name + "' has an edge from " + node_text(finished.xy, a) +
                  " to " + node_text(finished.xy, b) + " that is not a side of any triangle");
    if (seen.insert(edge_key(std::min(a, b), std::max(a, b))).second) edges.push_back({a, b});
  }
  return edges;
}

/// Nodes and triangles in the new numbers, elements sorted by their lowest node.
void place_elements(const TaggedMesh& raw, const std::vector<std::int32_t>& oriented,
                    const std::vector<std::int32_t>& number, TaggedMesh& out) {
  const std::size_t num_nodes = static_cast<std::size_t>(
      std::count_if(number.begin(), number.end(), [](std::int32_t n) { return n >= 0; }));
  out.mesh.xy.resize(2 * num_nodes);
  for (std::size_t n = 0; n < number.size(); ++n)
    if (number[n] >= 0) {
      out.mesh.xy[2 * number[n]] = raw.mesh.xy[2 * n];
      out.mesh.xy[2 * number[n] + 1] = raw.mesh.xy[2 * n + 1];
    }
  const std::size_t num_elements = oriented.size() / 3;
  auto lowest = [&](std::size_t e) {
    return std::min(
        {number[oriented[3 * e]], number[oriented[3 * e + 1]], number[oriented[3 * e + 2]]});
  };
  std::vector<std::size_t> element_order(num_elements);
  std::iota(element_order.begin(), element_order.end(), std::size_t{0});
  std::stable_sort(element_order.begin(), element_order.end(),
                   [&](std::size_t a, std::size_t b) { return lowest(a) < lowest(b); });
  out.mesh.triangles.reserve(oriented.size());
  for (const std::size_t e : element_order) {
    for (int k = 0; k < 3; ++k) out.mesh.triangles.push_back(number[oriented[3 * e + k]]);
    out.mesh.element_surface.push_back(raw.mesh.element_surface[e]);
    out.element_tags.push_back(raw.element_tags[e]);
  }
  out.mesh.surface_body = raw.mesh.surface_body;
}

}  // namespace

TaggedMesh finish_mesh(const TaggedMesh& raw, const MeshSource& source) {
  if (raw.mesh.triangles.empty()) source.fail("the mesh has no triangles");
  const std::vector<char> used = nodes_on_triangles(raw.mesh.num_nodes(), raw.mesh.triangles);
  require_on_triangles(raw.mesh, used, source);
  std::vector<std::int32_t> oriented = raw.mesh.triangles;
  turn_counter_clockwise(raw.mesh.xy, oriented);
  const std::vector<std::int32_t> number = new_node_numbers(used, oriented);

  TaggedMesh out;
  place_elements(raw, oriented, number, out);
  std::unordered_set<std::uint64_t> sides;
  for (std::size_t e = 0; e < out.mesh.triangles.size(); e += 3)
    for (int k = 0; k < 3; ++k)
      sides.insert(edge_key(out.mesh.triangles[e + k], out.mesh.triangles[e + (k + 1) % 3]));
  for (const auto& [name, edges] : raw.mesh.curves)
    out.mesh.curves[name] = curve_edges(name, edges, number, sides, out.mesh, source);
  for (const auto& [name, nodes] : raw.mesh.points) {
    auto& mapped = out.mesh.points[name];
    for (const std::int32_t n : nodes) mapped.push_back(number[n]);
    std::sort(mapped.begin(), mapped.end());
    mapped.erase(std::unique(mapped.begin(), mapped.end()), mapped.end());
  }
  return out;
}

}  // namespace rockdd

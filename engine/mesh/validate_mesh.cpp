#include "engine/mesh/validate_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/scene/geometry_limits.hpp"

namespace rockdd {

namespace {

/// How messages call element e.
struct ElementNames {
  std::span<const std::size_t> labels;
  std::string operator()(std::size_t e) const {
    return "element " + std::to_string(labels.empty() ? e : labels[e]);
  }
};

std::string nodes_text(const Mesh& mesh, std::size_t e) {
  std::string text = "nodes at ";
  for (int k = 0; k < 3; ++k) {
    const std::int32_t n = mesh.triangles[3 * e + k];
    text += (k ? ", " : "") + point_text(mesh.xy[2 * n], mesh.xy[2 * n + 1]);
  }
  return text;
}

void check_sizes(const Mesh& mesh, const MeshSource& source) {
  if (mesh.xy.size() % 2 != 0) source.fail("xy has an odd number of coordinates");
  if (mesh.triangles.size() % 3 != 0) source.fail("triangles is not a list of node triples");
  if (mesh.triangles.empty()) source.fail("the mesh has no triangles");
  if (mesh.element_surface.size() != mesh.num_elements())
    source.fail("element_surface has " + std::to_string(mesh.element_surface.size()) +
                " entries for " + std::to_string(mesh.num_elements()) + " elements");
}

void check_nodes(const Mesh& mesh, const MeshSource& source, const ElementNames& name) {
  const auto num_nodes = static_cast<std::int64_t>(mesh.num_nodes());
  for (std::size_t n = 0; n < mesh.xy.size(); ++n) {
    if (!std::isfinite(mesh.xy[n]))
      source.fail("node " + std::to_string(n / 2) + " has a coordinate that is not finite");
    if (!coordinate_in_range(mesh.xy[n]))
      source.fail("expected node coordinates in [-" + format_number(kLongestLength) + ", " +
                  format_number(kLongestLength) + "] m, got node " + std::to_string(n / 2) +
                  " at " + point_text(mesh.xy[n - n % 2], mesh.xy[n - n % 2 + 1]));
  }
  std::vector<char> used(mesh.num_nodes(), 0);
  for (std::size_t e = 0; e < mesh.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = mesh.triangles[3 * e + k];
      if (n < 0 || n >= num_nodes)
        source.fail(name(e) + " refers to node " + std::to_string(n) + ", but the mesh has " +
                    std::to_string(num_nodes) + " nodes");
      used[n] = 1;
    }
  for (std::size_t n = 0; n < used.size(); ++n)
    if (!used[n])
      source.fail("node " + std::to_string(n) + " at " +
                  point_text(mesh.xy[2 * n], mesh.xy[2 * n + 1]) + " is on no triangle");
}

void check_surfaces(const Mesh& mesh, const MeshSource& source, const ElementNames& name) {
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    const std::int32_t s = mesh.element_surface[e];
    if (s < 0 || static_cast<std::size_t>(s) >= mesh.surface_body.size())
      source.fail(name(e) + " is on surface " + std::to_string(s) + ", but the mesh has " +
                  std::to_string(mesh.surface_body.size()) + " surfaces");
  }
}

double squared_diagonal(const Mesh& mesh) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::size_t i = 0; i < mesh.xy.size(); ++i) {
    lo[i % 2] = std::min(lo[i % 2], mesh.xy[i]);
    hi[i % 2] = std::max(hi[i % 2], mesh.xy[i]);
  }
  return (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]);
}

/// A mesh smaller than kShortestLength has areas that underflow: the relative zero-area test
/// below would compare 0 with 0 and pass. (Its largest extent is bounded by check_nodes.)
void check_extent(const Mesh& mesh, const MeshSource& source) {
  const double diagonal = std::sqrt(squared_diagonal(mesh));
  if (!(diagonal >= kShortestLength))
    source.fail("expected a mesh whose extent (bounding-box diagonal) is at least " +
                format_number(kShortestLength) + " m, got " + format_number(diagonal) + " m");
}

/// Each element's nodes within kMostElementSizesFromOrigin of its longest side from the
/// origin (geometry_limits): farther, rounding of the positions swamps its strains.
void check_precision(const Mesh& mesh, const MeshSource& source, const ElementNames& name) {
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    double farthest = 0.0, longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = mesh.triangles[3 * e + k], b = mesh.triangles[3 * e + (k + 1) % 3];
      farthest = std::max({farthest, std::abs(mesh.xy[2 * a]), std::abs(mesh.xy[2 * a + 1])});
      longest = std::max(longest, std::hypot(mesh.xy[2 * b] - mesh.xy[2 * a],
                                             mesh.xy[2 * b + 1] - mesh.xy[2 * a + 1]));
    }
    if (!keeps_precision(farthest, longest))
      source.fail("expected " + precision_expectation() + ", got " + name(e) + " of size " +
                  format_number(longest) + " m with " + nodes_text(mesh, e));
  }
}

/// A triangle of area below 1e-12 × (bounding-box diagonal)^2 is degenerate: its stiffness
/// would be singular or swamped by rounding.
void check_areas(const Mesh& mesh, const MeshSource& source, const ElementNames& name) {
  const double smallest = 1e-12 * squared_diagonal(mesh);
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    const std::int32_t* t = &mesh.triangles[3 * e];
    const double ax = mesh.xy[2 * t[0]], ay = mesh.xy[2 * t[0] + 1];
    const double area = 0.5 * ((mesh.xy[2 * t[1]] - ax) * (mesh.xy[2 * t[2] + 1] - ay) -
                               (mesh.xy[2 * t[2]] - ax) * (mesh.xy[2 * t[1] + 1] - ay));
    if (std::abs(area) < smallest)
      source.fail(name(e) + " has zero area (" + nodes_text(mesh, e) + ")");
    if (area < 0.0) source.fail(name(e) + " is clockwise (" + nodes_text(mesh, e) + ")");
  }
}

void check_duplicates(const Mesh& mesh, const MeshSource& source, const ElementNames& name) {
  std::map<std::array<std::int32_t, 3>, std::size_t> first_with_nodes;
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    std::array<std::int32_t, 3> key{mesh.triangles[3 * e], mesh.triangles[3 * e + 1],
                                    mesh.triangles[3 * e + 2]};
    std::sort(key.begin(), key.end());
    const auto [it, inserted] = first_with_nodes.emplace(key, e);
    if (!inserted)
      source.fail(name(it->second) + " and " + name(e) + " are the same triangle (" +
                  nodes_text(mesh, e) + ")");
  }
}

void check_groups(const Mesh& mesh, const MeshSource& source) {
  const auto num_nodes = static_cast<std::int64_t>(mesh.num_nodes());
  auto check = [&](const std::string& group, std::int32_t n) {
    if (n < 0 || n >= num_nodes)
      source.fail(group + " refers to node " + std::to_string(n) + ", but the mesh has " +
                  std::to_string(num_nodes) + " nodes");
  };
  for (const auto& [name, edges] : mesh.curves)
    for (const auto& edge : edges) {
      check("physical curve '" + name + "'", edge[0]);
      check("physical curve '" + name + "'", edge[1]);
      if (edge[0] == edge[1])
        source.fail("physical curve '" + name + "' has an edge from node " +
                    std::to_string(edge[0]) + " to itself");
    }
  for (const auto& [name, nodes] : mesh.points)
    for (const std::int32_t n : nodes) check("physical point '" + name + "'", n);
}

}  // namespace

void validate_mesh(const Mesh& mesh, const MeshSource& source,
                   std::span<const std::size_t> element_labels) {
  const ElementNames name{element_labels};
  check_sizes(mesh, source);
  check_nodes(mesh, source, name);
  check_surfaces(mesh, source, name);
  check_extent(mesh, source);
  check_areas(mesh, source, name);
  check_precision(mesh, source, name);
  check_duplicates(mesh, source, name);
  check_groups(mesh, source);
}

void validate_mesh(const Mesh& mesh, const std::string& source) {
  validate_mesh(mesh, MeshSource{source, ""}, {});
}

}  // namespace rockdd

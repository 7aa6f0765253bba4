#include "engine/mesh/gmsh_model_reader.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace rockdd {

namespace {

constexpr int kLine2 = 1;      // Gmsh element type: 2-node line
constexpr int kTriangle3 = 2;  // 3-node triangle
constexpr int kPoint = 15;     // 1-node point

/// Gmsh's name for an element type, e.g. "Quadrilateral 4".
std::string element_type_name(int type) {
  std::string name;
  int dim = 0, order = 0, num_nodes = 0, num_primary = 0;
  std::vector<double> local_coords;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, num_nodes, local_coords,
                                          num_primary);
  return name;
}

[[noreturn]] void fail_unsupported(const MeshSource& source, int type) {
  source.fail("unsupported element type '" + element_type_name(type) + "' (only 3-node triangles)");
}

/// Every node Gmsh holds; `index` maps a Gmsh node tag to its position.
struct NodeTable {
  std::vector<double> xy;
  std::unordered_map<std::size_t, std::int32_t> index;
  std::int32_t at(std::size_t tag, const MeshSource& source) const {
    const auto it = index.find(tag);
    if (it == index.end())
      source.fail("an element refers to node " + std::to_string(tag) +
                  ", which the file does not define");
    return it->second;
  }
};

/// The mesh must lie in z = 0 (to a relative 1e-9 of its extent): the engine is plane.
void require_planar(const std::vector<std::size_t>& tags, const std::vector<double>& coord,
                    const MeshSource& source) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::size_t n = 0; n < tags.size(); ++n)
    for (int d = 0; d < 2; ++d) {
      lo[d] = std::min(lo[d], coord[3 * n + d]);
      hi[d] = std::max(hi[d], coord[3 * n + d]);
    }
  const double extent = tags.empty() ? 0.0 : std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
  for (std::size_t n = 0; n < tags.size(); ++n)
    if (std::abs(coord[3 * n + 2]) > 1e-9 * extent)
      source.fail("node " + std::to_string(tags[n]) + " is at z = " +
                  format_number(coord[3 * n + 2]) + " (a 2D mesh must lie in the plane z = 0)");
}

NodeTable read_nodes(const MeshSource& source) {
  std::vector<std::size_t> tags;
  std::vector<double> coord, parametric;
  gmsh::model::mesh::getNodes(tags, coord, parametric, -1, -1, false, false);
  require_planar(tags, coord, source);
  NodeTable nodes;
  nodes.xy.resize(2 * tags.size());
  nodes.index.reserve(tags.size());
  for (std::size_t n = 0; n < tags.size(); ++n) {
    nodes.xy[2 * n] = coord[3 * n];
    nodes.xy[2 * n + 1] = coord[3 * n + 1];
    nodes.index.emplace(tags[n], static_cast<std::int32_t>(n));
  }
  return nodes;
}

/// Volume elements have no place in a plane model; name the first type found.
void reject_volume_elements(const MeshSource& source) {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, 3);
  if (!types.empty()) fail_unsupported(source, types.front());
}

/// The physical surface name of a surface entity, "" if none; two different names are an error
/// since an element belongs to exactly one body.
std::string body_of_surface(int surface, const MeshSource& source) {
  std::vector<int> groups;
  gmsh::model::getPhysicalGroupsForEntity(2, surface, groups);
  std::string body;
  for (const int group : groups) {
    std::string name;
    gmsh::model::getPhysicalName(2, group, name);
    if (name.empty() || name == body) continue;
    if (!body.empty())
      source.fail("surface " + std::to_string(surface) + " is in two physical surfaces, '" + body +
                  "' and '" + name + "' (a surface belongs to one body)");
    body = name;
  }
  return body;
}

void read_surfaces(const NodeTable& nodes, const MeshSource& source, TaggedMesh& out) {
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  for (const auto& [dim, surface] : surfaces) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, surface);
    for (const int type : types)
      if (type != kTriangle3) fail_unsupported(source, type);
    if (types.empty() || element_tags.front().empty()) continue;
    const auto index = static_cast<std::int32_t>(out.mesh.surface_body.size());
    out.mesh.surface_body.push_back(body_of_surface(surface, source));
    for (std::size_t e = 0; e < element_tags.front().size(); ++e) {
      for (int k = 0; k < 3; ++k)
        out.mesh.triangles.push_back(nodes.at(node_tags.front()[3 * e + k], source));
      out.element_tags.push_back(element_tags.front()[e]);
      out.mesh.element_surface.push_back(index);
    }
  }
}

/// Named physical groups of dimension `dim` as (name, tag); unnamed ones are left out.
std::vector<std::pair<std::string, int>> named_groups(int dim) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  std::vector<std::pair<std::string, int>> named;
  for (const auto& [group_dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(group_dim, tag, name);
    if (!name.empty()) named.emplace_back(name, tag);
  }
  return named;
}

void read_curves(const NodeTable& nodes, const MeshSource& source, TaggedMesh& out) {
  for (const auto& [name, group] : named_groups(1)) {
    auto& edges = out.mesh.curves[name];  // groups sharing a name are merged
    std::vector<int> curves;
    gmsh::model::getEntitiesForPhysicalGroup(1, group, curves);
    for (const int curve : curves) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, curve);
      for (std::size_t t = 0; t < types.size(); ++t) {
        if (types[t] != kLine2) fail_unsupported(source, types[t]);
        for (std::size_t e = 0; e < element_tags[t].size(); ++e)
          edges.push_back(
              {nodes.at(node_tags[t][2 * e], source), nodes.at(node_tags[t][2 * e + 1], source)});
      }
    }
  }
}

void read_points(const NodeTable& nodes, const MeshSource& source, TaggedMesh& out) {
  for (const auto& [name, group] : named_groups(0)) {
    auto& point_nodes = out.mesh.points[name];
    std::vector<int> points;
    gmsh::model::getEntitiesForPhysicalGroup(0, group, points);
    for (const int point : points) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 0, point);
      for (std::size_t t = 0; t < types.size(); ++t) {
        if (types[t] != kPoint) fail_unsupported(source, types[t]);
        for (const std::size_t tag : node_tags[t]) point_nodes.push_back(nodes.at(tag, source));
      }
    }
  }
}

}  // namespace

TaggedMesh read_gmsh_model(const MeshSource& source) {
  reject_volume_elements(source);
  const NodeTable nodes = read_nodes(source);
  TaggedMesh out;
  out.mesh.xy = nodes.xy;
  read_surfaces(nodes, source, out);
  read_curves(nodes, source, out);
  read_points(nodes, source, out);
  return out;
}

}  // namespace rockdd

#include <algorithm>
#include <map>
#include <numeric>
#include <string>

#include "engine/common/errors.hpp"
#include "engine/mesh/mesh.hpp"
#include "engine/model/block_topology.hpp"
#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"
#include "kernels/cst.hpp"

namespace rockdd {
namespace {

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "none" : out;
}

/// Material index of each body: an exact body match first, else the "*" material.
std::vector<std::int32_t> material_of_bodies(const Scene& scene,
                                             const std::vector<std::string>& bodies,
                                             const std::vector<std::int32_t>& elements_per_body) {
  const std::string where = scene.file.string();
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const std::string& body = scene.materials[m].body;
    if (body != "*" && std::find(bodies.begin(), bodies.end(), body) == bodies.end())
      throw InputError(where, "material[" + std::to_string(m) + "].body",
                       "no physical surface named '" + body +
                           "' in the mesh (available: " + join_names(bodies) + ")");
  }
  std::vector<std::int32_t> material(bodies.size(), -1);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t m = 0; m < scene.materials.size(); ++m)
      if (scene.materials[m].body == bodies[b]) material[b] = static_cast<std::int32_t>(m);
    if (material[b] < 0)
      for (std::size_t m = 0; m < scene.materials.size(); ++m)
        if (scene.materials[m].body == "*") material[b] = static_cast<std::int32_t>(m);
    if (material[b] < 0) {
      const std::string name = bodies[b].empty() ? "(unnamed surface)" : "'" + bodies[b] + "'";
      throw InputError(where, "material",
                       "no [[material]] covers body " + name + " (" +
                           std::to_string(elements_per_body[b]) +
                           " elements): add one with body = \"" + bodies[b] + "\" or \"*\"");
    }
  }
  return material;
}

}  // namespace

std::vector<double> lumped_node_mass(const Model& model) {
  std::vector<double> mass(static_cast<std::size_t>(model.num_nodes()), 0.0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const double m = kernels::cst_lumped_mass(model.area0[e], model.density[e], model.thickness);
    for (int k = 0; k < 3; ++k) mass[model.conn[3 * e + k]] += m;
  }
  return mass;
}

Model build_model(const Scene& scene, const Mesh& mesh) {
  Model model;
  model.plane = scene.plane;
  model.thickness = scene.thickness;
  model.materials = scene.materials;
  const auto num_elements = static_cast<std::int32_t>(mesh.num_elements());
  const auto mesh_nodes = static_cast<std::int32_t>(mesh.num_nodes());
  const std::string where = scene.file.string();

  // Bodies are physical surface names; element -> body -> material.
  std::vector<std::int32_t> body_of_surface(mesh.surface_body.size());
  for (std::size_t s = 0; s < mesh.surface_body.size(); ++s) {
    auto& bodies = model.sets.bodies;
    auto it = std::find(bodies.begin(), bodies.end(), mesh.surface_body[s]);
    if (it == bodies.end()) it = bodies.insert(bodies.end(), mesh.surface_body[s]);
    body_of_surface[s] = static_cast<std::int32_t>(it - bodies.begin());
  }
  model.element_body.resize(static_cast<std::size_t>(num_elements));
  std::vector<std::int32_t> elements_per_body(model.sets.bodies.size(), 0);
  for (std::int32_t e = 0; e < num_elements; ++e) {
    model.element_body[e] = body_of_surface[mesh.element_surface[e]];
    ++elements_per_body[model.element_body[e]];
  }
  const auto material_of_body = material_of_bodies(scene, model.sets.bodies, elements_per_body);

  // Blocks: a shared edge binds its two elements unless a [[joint]] names their two bodies
  // (docs/scene.md: the common curve of conformal bodies becomes a joint, its nodes are split).
  const EdgeAdjacency adjacency = build_edge_adjacency(mesh.triangles, where.c_str());
  std::vector<std::uint8_t> intact(mesh.triangles.size(), 1);
  auto joint_between = [&](std::int32_t body_a, std::int32_t body_b) {
    const std::string& a = model.sets.bodies[body_a];
    const std::string& b = model.sets.bodies[body_b];
    for (const JointSpec& joint : scene.joints) {
      if (joint.between.size() == 1 && joint.between[0] == "*") return true;
      if (joint.between.size() == 2 && ((joint.between[0] == a && joint.between[1] == b) ||
                                        (joint.between[0] == b && joint.between[1] == a)))
        return true;
    }
    return false;
  };
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t other = adjacency.neighbor[3 * e + k];
      if (other < 0 || model.element_body[e] == model.element_body[other]) continue;
      if (joint_between(model.element_body[e], model.element_body[other])) intact[3 * e + k] = 0;
    }
  BlockTopology topo = form_blocks(mesh.triangles, mesh_nodes, adjacency, intact);
  model.conn = std::move(topo.conn);
  model.element_block = std::move(topo.element_block);
  model.num_blocks = topo.num_blocks;

  const auto num_nodes = static_cast<std::int32_t>(topo.node_origin.size());
  model.X.resize(2 * static_cast<std::size_t>(num_nodes));
  for (std::int32_t n = 0; n < num_nodes; ++n) {
    model.X[2 * n] = mesh.xy[2 * topo.node_origin[n]];
    model.X[2 * n + 1] = mesh.xy[2 * topo.node_origin[n] + 1];
  }
  model.u.assign(model.X.size(), 0.0);
  model.v.assign(model.X.size(), 0.0);
  model.node_block.assign(static_cast<std::size_t>(num_nodes), -1);
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) model.node_block[model.conn[3 * e + k]] = model.element_block[e];

  // Per-element material data (heterogeneity draws replace these values when enabled).
  model.element_material.resize(static_cast<std::size_t>(num_elements));
  model.young.resize(static_cast<std::size_t>(num_elements));
  model.poisson.resize(static_cast<std::size_t>(num_elements));
  model.density.resize(static_cast<std::size_t>(num_elements));
  model.area0.resize(static_cast<std::size_t>(num_elements));
  for (std::int32_t e = 0; e < num_elements; ++e) {
    const std::int32_t m = material_of_body[model.element_body[e]];
    model.element_material[e] = m;
    model.young[e] = scene.materials[m].young;
    model.poisson[e] = scene.materials[m].poisson;
    model.density[e] = scene.materials[m].density;
    double xy[6];
    for (int k = 0; k < 3; ++k) {
      xy[2 * k] = model.X[2 * model.conn[3 * e + k]];
      xy[2 * k + 1] = model.X[2 * model.conn[3 * e + k] + 1];
    }
    model.area0[e] = kernels::cst_signed_area(xy);
  }
  model.damage.assign(static_cast<std::size_t>(num_elements), 0.0);
  model.rotation.assign(static_cast<std::size_t>(num_elements), 0.0);
  model.rotation_cos.assign(static_cast<std::size_t>(num_elements), 1.0);
  model.rotation_sin.assign(static_cast<std::size_t>(num_elements), 0.0);
  model.strain.assign(3 * static_cast<std::size_t>(num_elements), 0.0);
  model.stress.assign(3 * static_cast<std::size_t>(num_elements), 0.0);
  model.node_mass = lumped_node_mass(model);
  model.node_root.resize(static_cast<std::size_t>(num_nodes));
  std::iota(model.node_root.begin(), model.node_root.end(), 0);

  // Named curves: each mesh edge maps to the element side that carries it.
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> slot_of_edge;
  for (std::int32_t e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = mesh.triangles[3 * e + k], b = mesh.triangles[3 * e + (k + 1) % 3];
      slot_of_edge.emplace(std::minmax(a, b), 3 * e + k);
    }
  for (const auto& [name, edges] : mesh.curves) {
    auto& out_edges = model.sets.curve_edges[name];
    auto& out_elements = model.sets.curve_edge_element[name];
    for (const auto& edge : edges) {
      const auto it = slot_of_edge.find(std::minmax(edge[0], edge[1]));
      if (it == slot_of_edge.end())
        throw InputError(where, "mesh",
                         "physical curve '" + name + "' has an edge (nodes " +
                             std::to_string(edge[0]) + ", " + std::to_string(edge[1]) +
                             ") that is not a side of any triangle");
      const std::int32_t e = it->second / 3, k = it->second % 3;
      out_edges.push_back(model.conn[3 * e + k]);
      out_edges.push_back(model.conn[3 * e + (k + 1) % 3]);
      out_elements.push_back(e);
    }
  }
  // Named points: every split copy of the point's node.
  std::vector<std::vector<std::int32_t>> copies(static_cast<std::size_t>(mesh_nodes));
  for (std::int32_t n = 0; n < num_nodes; ++n) copies[topo.node_origin[n]].push_back(n);
  for (const auto& [name, nodes] : mesh.points) {
    auto& out = model.sets.points[name];
    for (const std::int32_t n : nodes) out.insert(out.end(), copies[n].begin(), copies[n].end());
  }
  return model;
}

}  // namespace rockdd

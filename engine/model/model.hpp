#pragma once
// Model: the state of a simulation as structure-of-arrays, one contiguous array per field.
// Vector fields on nodes are interleaved (x, y) with 2 values per node, so a node's dofs
// are 2i and 2i+1 and a whole field is one array that the solver can read directly.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// Named parts of the model after blocks were formed and nodes split.
struct NamedSets {
  std::map<std::string, std::vector<std::int32_t>> curve_edges;         // 2 node ids per edge
  std::map<std::string, std::vector<std::int32_t>> curve_edge_element;  // element owning each edge
  std::map<std::string, std::vector<std::int32_t>> points;  // node ids (all split copies)
  std::vector<std::string> bodies;                          // body names (index = body id)
};

/// Nodes, elements, blocks and materials of one simulation.
struct Model {
  PlaneKind plane = PlaneKind::stress;
  double thickness = 1.0;

  // Nodes.
  std::vector<double> X;          // reference position
  std::vector<double> u;          // displacement
  std::vector<double> v;          // velocity
  std::vector<double> node_mass;  // lumped mass (kg), one per node
  std::vector<std::int32_t> node_block;
  std::vector<std::int32_t> node_root;  // the node it was split from by fracture (or itself)

  // Elements (CST, counter-clockwise).
  std::vector<std::int32_t> conn;              // 3 per element
  std::vector<std::int32_t> element_material;  // index into materials
  std::vector<std::int32_t> element_body;      // index into sets.bodies
  std::vector<std::int32_t> element_block;
  std::vector<double> young;  // undamaged E0 of each element
  std::vector<double> poisson;
  std::vector<double> density;
  std::vector<double> area0;   // reference area
  std::vector<double> damage;  // w in [0, 1]
  // Strengths of damageable elements (empty in an elastic scene): ft0, fc0 (Pa), phi (rad).
  std::vector<double> tensile_strength;
  std::vector<double> compressive_strength;
  std::vector<double> friction_angle;
  std::vector<double> rotation;  // angle of each element's co-rotational frame in K (rad)
  std::vector<double> rotation_cos;  // cos and sin of each rotation, set with it
  std::vector<double> rotation_sin;  // (set_element_rotation)
  std::vector<double> strain;    // 3 per element: exx, eyy, gxy
  std::vector<double> stress;    // 3 per element: sxx, syy, sxy

  std::int32_t num_blocks = 0;
  std::vector<MaterialSpec> materials;
  NamedSets sets;

  std::int32_t num_nodes() const { return static_cast<std::int32_t>(X.size() / 2); }
  std::int32_t num_elements() const { return static_cast<std::int32_t>(conn.size() / 3); }
};

/// Sets element e's stiffness frame to `angle`, with its cos and sin.
inline void set_element_rotation(Model& model, std::int32_t e, double angle) {
  const auto at = static_cast<std::size_t>(e);
  model.rotation[at] = angle;
  model.rotation_cos[at] = std::cos(angle);
  model.rotation_sin[at] = std::sin(angle);
}

struct Mesh;

/// Builds the model of a scene from its mesh: materials per element, blocks by edge
/// connectivity, nodes split between blocks, named curves/points mapped to the split nodes.
/// Throws InputError when an element has no material or a name is unknown.
Model build_model(const Scene& scene, const Mesh& mesh);

/// Lumped nodal masses (rho t A / 3 per element corner) of the current topology.
std::vector<double> lumped_node_mass(const Model& model);

/// Reference centroid (x, y) of element e.
inline std::array<double, 2> reference_centroid(const Model& model, std::int32_t e) {
  std::array<double, 2> c{0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const auto n = static_cast<std::size_t>(model.conn[3 * static_cast<std::size_t>(e) + k]);
    c[0] += model.X[2 * n] / 3.0;
    c[1] += model.X[2 * n + 1] / 3.0;
  }
  return c;
}

}  // namespace rockdd

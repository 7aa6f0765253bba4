#include "engine/contact/contact_rules.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

namespace rockdd {
namespace {

/// Spring of a sliding contact, as a fraction of ks, in analyses without inertia: about the
/// shear stiffness of a damaged element (a tenth of E0 t, against ks = 8 E0 t), so that the
/// open-close iteration moves a sliding contact most of the way to its friction limit per
/// iteration without throwing a fragment whose other contacts are open.
constexpr double kSlidingStiffnessFraction = 0.03;

}  // namespace

void set_contact_analysis(ContactParameters& parameters, Analysis analysis) {
  const bool inertia = analysis == Analysis::dynamic;
  parameters.sliding_stiffness =
      inertia ? 0.0 : kSlidingStiffnessFraction * parameters.shear_stiffness;
  parameters.forgive_unresisted_overlap = !inertia;
}

ContactRulebook contact_rules(const Scene& scene, const Model& model, const BlockBoundary& boundary,
                              Analysis analysis) {
  ContactRulebook rules;

  const auto num_bodies = static_cast<std::int32_t>(model.sets.bodies.size());
  rules.touching.num_bodies = num_bodies;
  rules.touching.allowed.assign(
      static_cast<std::size_t>(num_bodies) * static_cast<std::size_t>(num_bodies), 0);
  rules.joints.friction.assign(rules.touching.allowed.size(), 0.0);
  rules.joints.cohesion.assign(rules.touching.allowed.size(), 0.0);
  rules.joints.tensile.assign(rules.touching.allowed.size(), 0.0);
  auto body_index = [&](const std::string& name) {
    const auto& bodies = model.sets.bodies;
    return static_cast<std::int32_t>(std::find(bodies.begin(), bodies.end(), name) -
                                     bodies.begin());
  };
  std::optional<double> given_kn, given_ks;
  for (const JointSpec& joint : scene.joints) {
    // The springs are one pair for every contact: the last joint that gives one sets it, the
    // crack joint included.
    if (joint.normal_stiffness) given_kn = joint.normal_stiffness;
    if (joint.shear_stiffness) given_ks = joint.shear_stiffness;
    if (joint.between.size() == 1 && joint.between[0] == "crack") continue;  // fracture faces
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    if (joint.between.size() == 1 && joint.between[0] == "*") {
      for (std::int32_t i = 0; i < num_bodies; ++i)
        for (std::int32_t j = 0; j < num_bodies; ++j) pairs.emplace_back(i, j);
    } else if (joint.between.size() == 2) {
      pairs.emplace_back(body_index(joint.between[0]), body_index(joint.between[1]));
      pairs.emplace_back(pairs.back().second, pairs.back().first);
    }
    for (const auto& [i, j] : pairs) {
      if (i >= num_bodies || j >= num_bodies) continue;
      const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(num_bodies) +
                            static_cast<std::size_t>(j);
      rules.touching.allowed[k] = 1;
      rules.joints.friction[k] = std::tan(joint.friction_angle * std::numbers::pi / 180.0);
      rules.joints.cohesion[k] = joint.cohesion;
      rules.joints.tensile[k] = joint.tensile_strength;
    }
  }
  // Fracture faces (METHOD.md "Fracture"): blocks of one body that fracture separated touch
  // with the "crack" joint's properties, or else the material's friction angle and no
  // cohesion or tension.
  if (!model.tensile_strength.empty()) {
    const JointSpec* crack = nullptr;
    for (const JointSpec& joint : scene.joints)
      if (joint.between.size() == 1 && joint.between[0] == "crack") crack = &joint;
    std::vector<double> body_friction(static_cast<std::size_t>(num_bodies), 0.0);
    for (std::int32_t e = 0; e < model.num_elements(); ++e)
      body_friction[model.element_body[e]] =
          scene.materials[model.element_material[e]].friction_angle.value_or(0.0);
    for (std::int32_t b = 0; b < num_bodies; ++b) {
      const std::size_t k = static_cast<std::size_t>(b) * static_cast<std::size_t>(num_bodies) +
                            static_cast<std::size_t>(b);
      rules.touching.allowed[k] = 1;
      const double phi = crack ? crack->friction_angle : body_friction[b];
      rules.joints.friction[k] = std::tan(phi * std::numbers::pi / 180.0);
      rules.joints.cohesion[k] = crack ? crack->cohesion : 0.0;
      rules.joints.tensile[k] = crack ? crack->tensile_strength : 0.0;
    }
  }
  rules.touching.block_body.assign(static_cast<std::size_t>(model.num_blocks), 0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    rules.touching.block_body[model.element_block[e]] = model.element_body[e];
  // A block of fully broken elements (w = 1, the stiffness floor) is the open crack itself,
  // not a grain of rock: it takes no part in contact. As a contact body it could be crushed
  // to a point, and the copies of a node where several such fragments meet were pinched
  // between their neighbours' faces 10-25 um deep, in equilibrium with each other: hundreds
  // of joules in springs inside collapse steps, and a crack path that a 1e-9 change of the
  // load moved (docs/method-choices.md, "Fracture").
  if (!model.damage.empty()) {
    rules.touching.inert.assign(static_cast<std::size_t>(model.num_blocks), 1);
    for (std::int32_t e = 0; e < model.num_elements(); ++e)
      if (model.damage[e] < 1.0) rules.touching.inert[model.element_block[e]] = 0;
  }

  // Penalty springs scale with the stiffest material in contact (METHOD.md: about 10-100 E t).
  double stiffest = 0.0;
  for (const double e : model.young) stiffest = std::max(stiffest, e);
  rules.parameters.thickness = model.thickness;
  rules.parameters.normal_stiffness =
      given_kn ? *given_kn * model.thickness : 20.0 * stiffest * model.thickness;
  rules.parameters.shear_stiffness =
      given_ks ? *given_ks * model.thickness : 0.4 * rules.parameters.normal_stiffness;
  // Without inertia nothing but its own contacts holds a block tangentially, and friction as a
  // bare load would throw one that is held on one side only: a sliding contact keeps a
  // spring of a small fraction of ks (ContactParameters::sliding_stiffness).
  set_contact_analysis(rules.parameters, analysis);
  // Candidates within half the median boundary edge: near enough to close within a step.
  std::vector<double> lengths;
  for (std::size_t i = 0; i + 1 < boundary.edge_nodes.size(); i += 2) {
    const std::int32_t a = boundary.edge_nodes[i], b = boundary.edge_nodes[i + 1];
    lengths.push_back(
        std::hypot(model.X[2 * b] - model.X[2 * a], model.X[2 * b + 1] - model.X[2 * a + 1]));
  }
  // Each boundary vertex stands for half of its two boundary edges. Both faces of a joint
  // have their vertices in contact with the other, so a contact carries half of that: the
  // cohesion and tensile strength of a joint then act on its true length.
  rules.vertex_area.assign(boundary.vertices.size(), 0.0);
  for (std::size_t i = 0; i < lengths.size(); ++i)
    for (int end = 0; end < 2; ++end) {
      const auto v = std::lower_bound(boundary.vertices.begin(), boundary.vertices.end(),
                                      boundary.edge_nodes[2 * i + end]) -
                     boundary.vertices.begin();
      rules.vertex_area[v] += 0.25 * lengths[i] * model.thickness;
    }
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    rules.parameters.reach = 0.5 * lengths[lengths.size() / 2];
    // A quarter of the median edge: far beyond any penalty overlap of a sound solve
    // (force / kn), so deeper only when the iteration runs away.
    rules.parameters.penetration_limit = 0.5 * rules.parameters.reach;
  }
  return rules;
}

}  // namespace rockdd

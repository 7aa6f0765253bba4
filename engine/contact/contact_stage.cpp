#include "engine/contact/contact_stage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "kernels/contact_geometry.hpp"

namespace rockdd {
namespace {

/// The geometry of contact c at `positions`.
kernels::VertexEdge geometry(const Contact& c, std::span<const double> positions) {
  const double p[2] = {positions[2 * c.vertex], positions[2 * c.vertex + 1]};
  const double a[2] = {positions[2 * c.a], positions[2 * c.a + 1]};
  const double b[2] = {positions[2 * c.b], positions[2 * c.b + 1]};
  return kernels::vertex_edge(p, a, b);
}

/// v . (x_p, x_a, x_b) for a 6-vector over the contact's dofs and a 2-per-node field.
double dot_contact(const double v[6], const Contact& c, std::span<const double> field) {
  const std::int32_t nodes[3] = {c.vertex, c.a, c.b};
  double sum = 0.0;
  for (int k = 0; k < 3; ++k)
    sum += v[2 * k] * field[2 * nodes[k]] + v[2 * k + 1] * field[2 * nodes[k] + 1];
  return sum;
}

/// force += scale * v over the contact's dofs.
void add_to_nodes(const Contact& c, const double v[6], double scale, std::span<double> force) {
  const std::int32_t nodes[3] = {c.vertex, c.a, c.b};
  for (int k = 0; k < 3; ++k) {
    force[2 * nodes[k]] += scale * v[2 * k];
    force[2 * nodes[k] + 1] += scale * v[2 * k + 1];
  }
}

}  // namespace

ContactStage::ContactStage(const Scene& scene, const Model& model) {
  boundary_ = extract_block_boundary(model);
  const auto num_bodies = static_cast<std::int32_t>(model.sets.bodies.size());
  rules_.num_bodies = num_bodies;
  rules_.allowed.assign(static_cast<std::size_t>(num_bodies * num_bodies), 0);
  joint_friction_.assign(rules_.allowed.size(), 0.0);
  joint_cohesion_.assign(rules_.allowed.size(), 0.0);
  auto body_index = [&](const std::string& name) {
    const auto& bodies = model.sets.bodies;
    return static_cast<std::int32_t>(std::find(bodies.begin(), bodies.end(), name) -
                                     bodies.begin());
  };
  std::optional<double> given_kn, given_ks;
  for (const JointSpec& joint : scene.joints) {
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
      const std::size_t k = static_cast<std::size_t>(i * num_bodies + j);
      rules_.allowed[k] = 1;
      joint_friction_[k] = std::tan(joint.friction_angle * std::numbers::pi / 180.0);
      joint_cohesion_[k] = joint.cohesion;
    }
    if (joint.normal_stiffness) given_kn = joint.normal_stiffness;
    if (joint.shear_stiffness) given_ks = joint.shear_stiffness;
  }
  rules_.block_body.assign(static_cast<std::size_t>(model.num_blocks), 0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    rules_.block_body[model.element_block[e]] = model.element_body[e];

  // Penalty springs scale with the stiffest material in contact (METHOD.md: about 10-100 E t).
  double stiffest = 0.0;
  for (const double e : model.young) stiffest = std::max(stiffest, e);
  parameters_.thickness = model.thickness;
  parameters_.normal_stiffness =
      given_kn ? *given_kn * model.thickness : 20.0 * stiffest * model.thickness;
  parameters_.shear_stiffness =
      given_ks ? *given_ks * model.thickness : 0.4 * parameters_.normal_stiffness;
  // Candidates within half the median boundary edge: near enough to close within a step.
  std::vector<double> lengths;
  for (std::size_t i = 0; i + 1 < boundary_.edge_nodes.size(); i += 2) {
    const std::int32_t a = boundary_.edge_nodes[i], b = boundary_.edge_nodes[i + 1];
    lengths.push_back(
        std::hypot(model.X[2 * b] - model.X[2 * a], model.X[2 * b + 1] - model.X[2 * a + 1]));
  }
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    parameters_.reach = 0.5 * lengths[lengths.size() / 2];
    parameters_.gap_tolerance = 1e-4 * parameters_.reach;
  }
}

bool ContactStage::detect(std::span<const double> positions) {
  const auto candidates = detect_contacts(boundary_, positions, rules_, parameters_.reach);
  std::vector<Contact> next;
  next.reserve(candidates.size());
  bool changed = candidates.size() != contacts_.size();
  std::size_t old = 0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const ContactCandidate& cand = candidates[i];
    Contact c;
    c.vertex = cand.vertex;
    c.edge = cand.edge;
    c.a = boundary_.edge_nodes[2 * static_cast<std::size_t>(cand.edge)];
    c.b = boundary_.edge_nodes[2 * static_cast<std::size_t>(cand.edge) + 1];
    const std::int32_t body_v = rules_.block_body[boundary_.edge_block[cand.edge]];
    // The vertex's block: the block of the element that owns the edge is the other side.
    const auto vb =
        std::lower_bound(boundary_.vertices.begin(), boundary_.vertices.end(), c.vertex);
    const std::int32_t body_p =
        rules_.block_body[boundary_.vertex_block[vb - boundary_.vertices.begin()]];
    const std::size_t k = static_cast<std::size_t>(body_p * rules_.num_bodies + body_v);
    c.friction = joint_friction_[k];
    c.cohesion = joint_cohesion_[k];
    // Contacts are sorted by (vertex, edge) on both sides: a merge finds the persisting ones.
    while (old < contacts_.size() && std::make_pair(contacts_[old].vertex, contacts_[old].edge) <
                                         std::make_pair(c.vertex, c.edge))
      ++old;
    if (old < contacts_.size() && contacts_[old].vertex == c.vertex &&
        contacts_[old].edge == c.edge) {
      c.state = contacts_[old].state;
      c.shear_spring = contacts_[old].shear_spring;
      c.slip_sign = contacts_[old].slip_sign;
    } else {
      changed = true;
      const double gap = geometry(c, positions).gap;
      c.state = gap <= 0.0 ? (c.friction > 0.0 || c.cohesion > 0.0 ? ContactState::locked
                                                                   : ContactState::sliding)
                           : ContactState::open;
    }
    next.push_back(c);
  }
  contacts_ = std::move(next);
  step_start_.assign(positions.begin(), positions.end());
  return changed;
}

double ContactStage::step_slip(const double t[6], const Contact& c,
                               std::span<const double> positions) const {
  return dot_contact(t, c, positions) - dot_contact(t, c, step_start_);
}

std::vector<std::int32_t> ContactStage::triples() const {
  std::vector<std::int32_t> out;
  out.reserve(3 * contacts_.size());
  for (const Contact& c : contacts_) {
    out.push_back(c.vertex);
    out.push_back(c.a);
    out.push_back(c.b);
  }
  return out;
}

void ContactStage::add_springs(std::span<const double> positions, const StiffnessLayout& layout,
                               std::int32_t first_slot, std::span<double> values,
                               std::span<double> force) const {
  const double kn = parameters_.normal_stiffness, ks = parameters_.shear_stiffness;
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    if (c.state == ContactState::open) continue;
    const kernels::VertexEdge ve = geometry(c, positions);
    double g[6], t[6], k[36] = {};
    kernels::gap_gradient(ve, g);
    kernels::slip_gradient(ve, t);
    for (int r = 0; r < 6; ++r)
      for (int s = 0; s < 6; ++s) k[6 * r + s] = kn * g[r] * g[s];
    add_to_nodes(c, g, kn * ve.gap, force);
    if (c.state == ContactState::locked) {
      const double slip = c.shear_spring + step_slip(t, c, positions);
      for (int r = 0; r < 6; ++r)
        for (int s = 0; s < 6; ++s) k[6 * r + s] += ks * t[r] * t[s];
      add_to_nodes(c, t, ks * slip, force);
    } else {
      // Sliding: Coulomb friction opposes the slip, as a load computed from the normal force.
      const double normal_force = kn * std::max(-ve.gap, 0.0);
      add_to_nodes(c, t, c.slip_sign * c.friction * normal_force, force);
    }
    if (values.empty()) continue;
    const std::int32_t* to =
        &layout.scatter[static_cast<std::size_t>(first_slot + static_cast<std::int32_t>(i)) *
                        kElementUpperEntries];
    for (int r = 0; r < 6; ++r)
      for (int s = r; s < 6; ++s, ++to)
        if (*to >= 0) values[*to] += k[6 * r + s];
  }
}

int ContactStage::update_states(std::span<const double> positions, double& largest_penetration) {
  const double kn = parameters_.normal_stiffness, ks = parameters_.shear_stiffness;
  int changes = 0;
  largest_penetration = 0.0;
  for (Contact& c : contacts_) {
    const kernels::VertexEdge ve = geometry(c, positions);
    double t[6];
    kernels::slip_gradient(ve, t);
    ContactState next = ContactState::open;
    if (ve.gap <= 0.0) {
      largest_penetration = std::max(largest_penetration, -ve.gap);
      const double normal_force = -kn * ve.gap;
      const double capacity =
          c.friction * normal_force + c.cohesion * 0.5 * ve.length * parameters_.thickness;
      const double slip_in_step = step_slip(t, c, positions);
      if (c.state == ContactState::sliding && slip_in_step * c.slip_sign > 0.0) {
        next = ContactState::sliding;  // keeps sliding the same way
      } else {
        const double shear =
            ks * ((c.state == ContactState::locked ? c.shear_spring : 0.0) + slip_in_step);
        // Without friction or cohesion a contact can only slide.
        next = capacity <= 0.0 || std::abs(shear) > capacity ? ContactState::sliding
                                                             : ContactState::locked;
        if (next == ContactState::sliding) c.slip_sign = shear > 0.0 ? 1.0 : -1.0;
      }
    }
    if (next != c.state) {
      // A closed contact that opens by less than the tolerance changes state but does not
      // hold the iteration back: re-solving would close it again and cycle.
      const bool flicker = next == ContactState::open && ve.gap <= parameters_.gap_tolerance;
      if (!flicker) ++changes;
      // A contact that locks now holds the edge point where it is: its spring starts unstretched
      // here, not where the step began.
      c.shear_spring = next == ContactState::locked ? -step_slip(t, c, positions) : 0.0;
      c.state = next;
    }
  }
  return changes;
}

void ContactStage::commit(std::span<const double> positions) {
  for (Contact& c : contacts_) {
    if (c.state != ContactState::locked) {
      c.shear_spring = 0.0;
      continue;
    }
    const kernels::VertexEdge ve = geometry(c, positions);
    double t[6];
    kernels::slip_gradient(ve, t);
    c.shear_spring += step_slip(t, c, positions);
  }
}

}  // namespace rockdd

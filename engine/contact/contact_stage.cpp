#include "engine/contact/contact_stage.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "kernels/contact_energy.hpp"
#include "kernels/contact_geometry.hpp"

namespace rockdd {
namespace {

/// The softest a sliding contact's spring gets, as a fraction of its first stiffness.
constexpr double kMinSlidingStiffness = 1.0 / 64.0;

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

/// Stores the gap and slip of contact c linearised about `positions` (the step start).
void linearise(Contact& c, std::span<const double> positions) {
  const kernels::VertexEdge ve = geometry(c, positions);
  kernels::gap_gradient(ve, c.g);
  kernels::slip_gradient(ve, c.t);
  c.gap_offset = ve.gap - dot_contact(c.g, c, positions);
  c.slip_offset = -dot_contact(c.t, c, positions);
  c.gap_start = ve.gap;
}

/// Faces closer than this share of the contact reach touch (meshed onto each other, up to
/// round-off).
constexpr double kTouchingGap = 1e-9;

double linear_gap(const Contact& c, std::span<const double> positions) {
  return c.gap_offset + dot_contact(c.g, c, positions);
}

/// Slip since the start of the step.
double step_slip(const Contact& c, std::span<const double> positions) {
  return c.slip_offset + dot_contact(c.t, c, positions);
}

}  // namespace

double contact_force_scale(const Model& model, std::span<const double> reaction,
                           std::span<const double> f_ext) {
  double scale = 0.0;
  for (std::size_t d = 0; d < model.X.size(); ++d)
    scale = std::max({scale, std::abs(reaction[d]), std::abs(f_ext[d])});
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    const double* sigma = &model.stress[3 * static_cast<std::size_t>(e)];
    const double largest = std::max({std::abs(sigma[0]), std::abs(sigma[1]), std::abs(sigma[2])});
    scale = std::max(scale, largest * std::sqrt(2.0 * model.area0[e]) * model.thickness);
  }
  return scale;
}

ContactStage::ContactStage(const Scene& scene, const Model& model, Analysis analysis,
                           Integrator integrator)
    : ContactStage(scene, model, build_edge_adjacency(model.conn, "model"), analysis, integrator) {}

ContactStage::ContactStage(const Scene& scene, const Model& model, const EdgeAdjacency& edges,
                           Analysis analysis, Integrator integrator)
    : boundary_(extract_block_boundary(model, edges)),
      rules_(contact_rules(scene, model, boundary_, analysis)),
      energy_consistent_(analysis == Analysis::dynamic && integrator == Integrator::newmark) {}

void ContactStage::mark_touching_nodes(std::span<std::uint8_t> node_mask) const {
  for (const Contact& c : contacts_)
    if (c.state != ContactState::open) node_mask[c.vertex] = node_mask[c.a] = node_mask[c.b] = 1;
}

double ContactStage::normal_stiffness(const Contact& c) const {
  if (energy_consistent_) return c.normal_spring;
  return c.state != ContactState::open ? rules_.parameters.normal_stiffness : 0.0;
}

std::vector<ContactSprings> ContactStage::springs() const {
  std::vector<ContactSprings> out(contacts_.size());
  for (std::size_t i = 0; i < contacts_.size(); ++i)
    out[i] = {normal_stiffness(contacts_[i]), shear_stiffness(contacts_[i])};
  return out;
}

const ContactStage::SpringChanges& ContactStage::spring_changes(
    std::span<const ContactSprings> before, std::span<const std::int32_t> equation) {
  LowRankTerms& added = spring_changes_.added;
  LowRankTerms& removed = spring_changes_.removed;
  added.clear();
  removed.clear();
  auto column = [&](const Contact& c, const double v[6], double k, LowRankTerms& out) {
    const std::int32_t nodes[3] = {c.vertex, c.a, c.b};
    std::int32_t rows[6];
    double values[6];
    const double scale = std::sqrt(k);
    for (int n = 0; n < 3; ++n)
      for (int d = 0; d < 2; ++d) {
        rows[2 * n + d] = equation[2 * static_cast<std::size_t>(nodes[n]) + d];
        values[2 * n + d] = scale * v[2 * n + d];
      }
    out.add_column(rows, values);
  };
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    const double normal_change = normal_stiffness(c) - before[i].normal_stiffness;
    if (normal_change != 0.0)
      column(c, c.g, std::abs(normal_change), normal_change > 0.0 ? added : removed);
    const double shear_change = shear_stiffness(c) - before[i].shear_stiffness;
    if (shear_change != 0.0)
      column(c, c.t, std::abs(shear_change), shear_change > 0.0 ? added : removed);
  }
  return spring_changes_;
}

void ContactStage::set_analysis(Analysis analysis, Integrator integrator) {
  set_contact_analysis(rules_.parameters, analysis);
  energy_consistent_ = analysis == Analysis::dynamic && integrator == Integrator::newmark;
}

void ContactStage::carry_contacts_from(const ContactStage& old, std::vector<Contact>& committed) {
  // Boundary edges are renumbered; a contact keeps its state if its edge still exists.
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> edge_of;
  for (std::size_t i = 0; 2 * i + 1 < boundary_.edge_nodes.size(); ++i)
    edge_of[{boundary_.edge_nodes[2 * i], boundary_.edge_nodes[2 * i + 1]}] =
        static_cast<std::int32_t>(i);
  std::vector<Contact> kept;
  for (Contact c : committed) {
    const auto found = edge_of.find({c.a, c.b});
    if (found == edge_of.end()) continue;
    c.edge = found->second;
    kept.push_back(c);
  }
  std::sort(kept.begin(), kept.end(), [](const Contact& x, const Contact& y) {
    return x.vertex != y.vertex ? x.vertex < y.vertex : x.edge < y.edge;
  });
  committed = std::move(kept);
  contacts_ = committed;
  started_ = old.started_;
  shear_swings_settled_ = old.shear_swings_settled_;
  normal_swings_settled_ = old.normal_swings_settled_;
}

bool ContactStage::detect(std::span<const double> positions, std::span<const Contact> committed) {
  const auto candidates =
      detect_contacts(boundary_, positions, rules_.touching, rules_.parameters.reach);
  std::vector<Contact> next;
  next.reserve(candidates.size());
  bool changed = candidates.size() != contacts_.size();
  // A redone step starts again from the committed contacts, not from its failed attempt.
  for (const ContactCandidate& cand : candidates) {
    Contact c;
    c.vertex = cand.vertex;
    c.edge = cand.edge;
    c.a = boundary_.edge_nodes[2 * static_cast<std::size_t>(cand.edge)];
    c.b = boundary_.edge_nodes[2 * static_cast<std::size_t>(cand.edge) + 1];
    const std::int32_t edge_block = boundary_.edge_block[cand.edge];
    const auto vb =
        std::lower_bound(boundary_.vertices.begin(), boundary_.vertices.end(), c.vertex);
    const std::int32_t vertex_block = boundary_.vertex_block[vb - boundary_.vertices.begin()];
    const std::size_t k = static_cast<std::size_t>(rules_.touching.block_body[vertex_block]) *
                              static_cast<std::size_t>(rules_.touching.num_bodies) +
                          static_cast<std::size_t>(rules_.touching.block_body[edge_block]);
    c.friction = rules_.joints.friction[k];
    c.cohesion = rules_.joints.cohesion[k];
    c.tensile_strength = rules_.joints.tensile[k];
    c.area = rules_.vertex_area[vb - boundary_.vertices.begin()];
    // What the contact remembers comes from the same pair, or else from the same vertex
    // against the same block: a vertex sliding onto the next edge keeps sliding (starting it
    // locked again would catch the block at every mesh node it passes).
    const Contact* before = nullptr;
    auto old = std::lower_bound(committed.begin(), committed.end(), c.vertex,
                                [](const Contact& x, std::int32_t v) { return x.vertex < v; });
    for (; old != committed.end() && old->vertex == c.vertex; ++old) {
      if (old->edge == c.edge) {
        before = &*old;
        break;
      }
      if (boundary_.edge_block[old->edge] == edge_block && old->state != ContactState::open)
        before = &*old;
    }
    if (before == nullptr || before->edge != c.edge) changed = true;
    if (before != nullptr) {
      c.state = before->state;
      c.shear_spring = before->shear_spring;
      c.slip_sign = before->slip_sign;
      c.friction_force = before->friction_force;
      c.bonded = before->bonded;
    } else {
      const double gap = geometry(c, positions).gap;
      // Faces meshed onto each other touch up to round-off: they start closed, and a joint
      // with cohesion or tensile strength holds them bonded until it slides or opens; faces
      // that meet later touch without a bond.
      const bool touching = gap <= kTouchingGap * rules_.parameters.reach;
      c.bonded = touching && !started_ && (c.cohesion > 0.0 || c.tensile_strength > 0.0);
      c.state = !touching                      ? ContactState::open
                : c.friction > 0.0 || c.bonded ? ContactState::locked
                                               : ContactState::sliding;
      // With inertia, a vertex that touches after the first step (it slid onto a face, or its
      // contact opened in the last step) starts sliding with no friction load: its first
      // solve then gives the slip that Coulomb's law is checked against. Started locked, its
      // spring ks would stop a sliding block dead in that solve, and the contacts around it,
      // seeing the block arrested, would read that as friction holding them and lock too:
      // the DDA update v1 = 2 du / dt - v0 turned such an arrest into a bounce
      // (docs/method-choices.md, "Friction with inertia").
      if (touching && started_ && !c.bonded && rules_.parameters.sliding_stiffness == 0.0) {
        c.state = ContactState::sliding;
        c.friction_force = 0.0;
        c.slip_sign = 0.0;
      }
    }
    c.slide_stiffness = rules_.parameters.sliding_stiffness;
    c.anchor_start = c.shear_spring;
    linearise(c, positions);
    // The step starts from the force the contact ended the last step with. Between two steps
    // the gap is measured anew, exactly, where the last solve used its linearisation; and a
    // vertex may be found already overlapping, having slid unseen off a split corner or onto
    // another edge. The overlap that no solve resisted carries no force: it is the contact's
    // zero, kept from step to step (open or closed) while the faces still overlap that much,
    // so it heals as they part. Otherwise it would push the faces apart with a force that
    // nothing did work for (penalty springs are 20 E t: a micrometre is meganewtons).
    const double resisted = before != nullptr && before->state != ContactState::open
                                ? std::min(before->end_gap, 0.0)
                                : 0.0;
    // With inertia the push-back of a new overlap is part of the momentum balance: every
    // pair that can close within a step is a candidate at its start (the step reach sees to
    // that, unless time.max_step_displacement allows more), and its contact resists the
    // approach. A pair the last step did not have at all
    // but finds overlapping is one that a change of topology made: a detachment that split a
    // block (a vertex and an edge of what was one block overlap through the broken element
    // that stood between them), or copies of a split node leaving the corner they shared. No
    // solve resisted that overlap and no work made it, so with inertia too it is forgiven;
    // in the first step the scene's own overlaps still push.
    // With Newmark's energy-consistent normal force the same holds for a pair that persists:
    // its spring takes up the step from the energy the last commit booked, and an overlap
    // beyond that, or a tension where the faces have parted, would be energy made by
    // measuring the gap anew (a closed contact's linearised end gap and its exact gap differ
    // by O(du^2 / L), micrometres for a block sliding 5 mm a step, where kn = 20 E t turns
    // 1.6 um into 0.26 J).
    const bool forgiving = rules_.parameters.forgive_unresisted_overlap || energy_consistent_;
    const bool forgive = forgiving || (before == nullptr && started_);
    double overlap =
        before != nullptr ? std::min(before->unresisted_overlap, std::max(-c.gap_start, 0.0)) : 0.0;
    if (c.state != ContactState::open && forgive)
      overlap = std::max(overlap, resisted - c.gap_start);
    // An open contact holds no energy: with Newmark's energy-consistent forces, one that
    // starts overlapping (the last step's linearised gap said apart, or a swing left it open)
    // has its zero there, or closing it would make the energy of that overlap.
    if (energy_consistent_ && c.state == ContactState::open)
      overlap = std::max(overlap, -c.gap_start);
    c.unresisted_overlap = overlap;
    c.gap_offset += overlap;
    c.gap_start += overlap;
    // Without inertia, a contact that ended the last step closed but is found apart (its
    // faces parted by more than the linearised gap said, or a detachment moved them) starts
    // open, as a new pair that far apart would: closed, its spring would pull the faces
    // together in the first solve, in tension no unbonded face holds, and a step of no length
    // would count that spring's energy as stored before any solve.
    if (forgiving && before != nullptr && !c.bonded && c.state != ContactState::open &&
        c.gap_start > kTouchingGap * rules_.parameters.reach) {
      c.state = ContactState::open;
      c.shear_spring = 0.0;
      c.friction_force = 0.0;
      c.slip_sign = 0.0;
    }
    c.start_normal_force = c.state != ContactState::open && c.gap_start < 0.0
                               ? -rules_.parameters.normal_stiffness * c.gap_start
                               : -1.0;
    c.closed_at_start = c.state != ContactState::open;
    c.locked_at_start = c.state == ContactState::locked;
    c.shear_spring_start = c.shear_spring;
    // The first solve takes the step's mean normal force as if the state held over the step.
    if (energy_consistent_) follow_mean_normal_force(c, c.gap_start, 0.0);
    next.push_back(c);
  }
  contacts_ = std::move(next);
  return changed;
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

void ContactStage::add_spring_forces(std::span<const double> positions,
                                     std::span<double> force) const {
  const double kn = rules_.parameters.normal_stiffness, ks = rules_.parameters.shear_stiffness;
  for (const Contact& c : contacts_) {
    if (c.state == ContactState::open) continue;
    add_to_nodes(c, c.g, kn * linear_gap(c, positions), force);
    if (c.state == ContactState::locked)
      add_to_nodes(c, c.t, ks * (c.shear_spring + step_slip(c, positions)), force);
    else  // sliding: Coulomb friction opposes the slip, as a load from the last normal force,
          // and without inertia a spring k_slide on the slip since (see ContactParameters)
      add_to_nodes(c, c.t,
                   -c.friction_force + c.slide_stiffness * (step_slip(c, positions) - c.slide_slip),
                   force);
  }
}

void ContactStage::add_solve_forces(std::span<const double> positions,
                                    std::span<double> force) const {
  if (!energy_consistent_) {
    add_spring_forces(positions, force);
    return;
  }
  const double ks = rules_.parameters.shear_stiffness;
  for (const Contact& c : contacts_) {
    const double normal =
        c.normal_force_line + c.normal_spring * (linear_gap(c, positions) - c.normal_gap_line);
    if (normal != 0.0) add_to_nodes(c, c.g, normal, force);
    // The shear: a spring locked over the whole step takes the trapezoid, which its energy
    // follows exactly; otherwise twice the end force (friction, a spring that locked or let
    // go within the step), whose work over the slip never exceeds what the spring held and
    // friction took.
    if (c.state == ContactState::locked) {
      const double end = ks * (c.shear_spring + step_slip(c, positions));
      add_to_nodes(c, c.t, c.locked_at_start ? ks * c.shear_spring_start + end : 2.0 * end, force);
    } else if (c.state == ContactState::sliding) {
      const double end =
          -c.friction_force + c.slide_stiffness * (step_slip(c, positions) - c.slide_slip);
      add_to_nodes(c, c.t, 2.0 * end, force);
    } else if (c.closed_at_start) {  // opened within the step: friction while it pressed
      add_to_nodes(c, c.t, -2.0 * c.friction_force, force);
    }
  }
}

bool ContactStage::follow_mean_normal_force(Contact& c, double gap, double tolerance) const {
  const kernels::MeanNormalForce mean =
      kernels::mean_normal_force(c.closed_at_start, c.state != ContactState::open, c.gap_start, gap,
                                 rules_.parameters.normal_stiffness);
  // The solve takes twice the mean: Newmark's equation holds the sum of the step's two end
  // forces, which the mean replaces.
  const double assumed = c.normal_force_line + c.normal_spring * (gap - c.normal_gap_line);
  c.normal_force_line = 2.0 * mean.force;
  c.normal_spring = 2.0 * mean.stiffness;
  c.normal_gap_line = gap;
  return std::abs(c.normal_force_line - assumed) > tolerance;
}

const SlotMatrices& ContactStage::spring_matrices(std::int32_t first_slot) {
  SlotMatrices& matrices = spring_matrices_;
  matrices.clear();
  const double kn = rules_.parameters.normal_stiffness;
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    // kn g g^T, plus ks t t^T locked or the sliding spring k_slide t t^T sliding; with
    // Newmark the normal spring is the mean normal force's tangent, which a spring that opens
    // in the step keeps.
    const double k_normal = energy_consistent_              ? c.normal_spring
                            : c.state != ContactState::open ? kn
                                                            : 0.0;
    const double k_shear = shear_stiffness(c);
    if (k_normal == 0.0 && c.state == ContactState::open) continue;
    double* ku = matrices.add(first_slot + static_cast<std::int32_t>(i));
    for (int r = 0; r < 6; ++r)
      for (int s = r; s < 6; ++s, ++ku)
        *ku = k_normal * c.g[r] * c.g[s] + k_shear * c.t[r] * c.t[s];
  }
  return matrices;
}

int ContactStage::update_states(std::span<const double> positions, double tolerance_scale,
                                bool settle, double& largest_penetration) {
  const double kn = rules_.parameters.normal_stiffness;
  largest_penetration = 0.0;
  double largest_gap = 0.0;  // the largest normal force, over kn: penetration or bond tension
  for (const Contact& c : contacts_)
    if (c.state != ContactState::open) {
      const double gap = linear_gap(c, positions);
      largest_penetration = std::max(largest_penetration, -gap);
      largest_gap = std::max(largest_gap, std::abs(gap));
    }
  // An iteration that ran away settles nothing: it must come back within the limit.
  const bool runaway = largest_penetration > rules_.parameters.penetration_limit;
  if (runaway) settle = false;
  // The iteration has settled when the forces the solve assumed match the states its result
  // implies, to a small fraction of the largest contact force (or of the forces that flow
  // through the elements, when the contacts carry less). Contacts that carry next to nothing
  // would otherwise flip back and forth forever: a contact changes between open and closed
  // only when its gap leaves the band [-tolerance, tolerance] / kn, and a change of shear
  // force smaller than the tolerance does not hold the iteration back.
  const double tolerance = tolerance_scale * rules_.parameters.force_tolerance *
                           std::max(kn * largest_gap, force_scale_);
  const double band = tolerance / kn;
  int changes = 0;
  for (Contact& c : contacts_) {
    const double gap = linear_gap(c, positions);
    const ContactState before = c.state;
    const bool was_closed = before != ContactState::open;
    // A contact that has already gone back and forth in this step stays closed while it
    // pulls less than a tenth of the largest contact force: the answer lies between its
    // two states, and either is within tolerance of it. A bonded one holds up to its
    // tensile strength.
    const double tension_capacity = c.bonded ? c.tensile_strength * c.area : 0.0;
    bool closed = was_closed ? gap <= band || (c.flips >= 2 && gap <= 10.0 * band) ||
                                   kn * gap <= tension_capacity
                             : gap < -band;
    // Settling, a contact that has gone back and forth and would flip again is left open:
    // open adds no force; the overlap it allows is what one iteration moved it, and the next
    // step starts it again from the geometry.
    if (settle && c.flips >= 2 && closed != was_closed) {
      if (was_closed) ++normal_swings_settled_;
      closed = false;
    } else if (closed != was_closed) {
      ++c.flips;
      ++changes;
    }
    if (!closed) {
      c.bonded = false;  // pulled apart: the bond is broken for good
      c.state = ContactState::open;
      c.shear_spring = 0.0;
      continue;
    }
    const double slip = step_slip(c, positions);
    if (!was_closed) {
      // It touched during the step, where its gap crossed zero (linear in between): that is
      // its anchor. Anchoring it at the end of the step would let it skip a step of sliding,
      // and a block whose contacts chatter would lose that much friction at every touch.
      // With Newmark's energy-consistent forces friction acts over the whole step, from the
      // mean normal force, which already holds the share of the step the contact was closed.
      const double touched =
          c.gap_start > 0.0 && !energy_consistent_ ? c.gap_start / (c.gap_start - gap) : 0.0;
      c.shear_spring = -std::clamp(touched, 0.0, 1.0) * slip;
      c.anchor_start = c.shear_spring;
    }
    const ShearUpdate shear = rules_.parameters.sliding_stiffness > 0.0
                                  ? update_shear_without_inertia(c, gap, slip, tolerance)
                                  : update_shear_with_inertia(c, gap, slip, tolerance);
    changes += shear.bond_broke ? 1 : 0;
    if (was_closed && std::abs(shear.implied - shear.assumed) > tolerance) {
      // Settling, a contact whose shear has already swung keeps the state this solve implies
      // without holding the iteration back.
      if (settle && c.shear_swings >= 2) {
        ++shear_swings_settled_;
      } else {
        ++changes;
        if (c.shear_swings < 255) ++c.shear_swings;
      }
    }
  }
  // With Newmark, the step's mean normal force is followed by Newton steps: a contact whose
  // force the solve took off its tangent by more than the tolerance holds the iteration back.
  if (energy_consistent_)
    for (Contact& c : contacts_) {
      const double gap = linear_gap(c, positions);
      if (follow_mean_normal_force(c, gap, tolerance)) ++changes;
      // A spring that opens within the step pressed for part of it: friction acts over that
      // part, from the mean normal force, against the step's slip.
      if (c.state == ContactState::open && c.closed_at_start) {
        const double slip = step_slip(c, positions);
        const double capacity = c.friction * std::max(-0.5 * c.normal_force_line, 0.0);
        double force = slip > 0.0 ? -capacity : slip < 0.0 ? capacity : 0.0;
        // Friction that reverses the slip it opposes cannot choose a direction: the contact,
        // which has no spring to stick with, carries none for the rest of the attempt.
        if (force * c.friction_force < 0.0 && c.shear_swings < 255) ++c.shear_swings;
        if (c.shear_swings >= 1) force = 0.0;
        if (std::abs(force - c.friction_force) > tolerance) ++changes;
        c.friction_force = force;
      }
    }
  return runaway ? std::max(changes, 1) : changes;
}

double ContactStage::friction_normal_force(Contact& c, double gap) const {
  // A contact in tension holds none. Friction is coupled to the normal force explicitly (the
  // last solve's), which need not converge: near a crack the normal forces of neighbouring
  // contacts move each other's friction, and a wedged fragment's friction presses it in
  // harder, which raises the friction again. Once a contact's shear has gone back and forth,
  // friction takes the normal force it had at the start of the step, if it was pressed then
  // (lagged by a step, like the load), or else the mean of this normal force and the one it
  // used last, which damps the swing; when the iteration settles the two agree.
  // With Newmark's energy-consistent forces, friction takes the normal force the step took:
  // its mean (half the sum the solve holds), not the end force, which at a landing is several
  // times the mean and would hold a sliding block.
  double normal_force =
      energy_consistent_
          ? std::max(-0.5 * (c.normal_force_line + c.normal_spring * (gap - c.normal_gap_line)),
                     0.0)
          : std::max(-rules_.parameters.normal_stiffness * gap, 0.0);
  // (With Newmark's mean normal forces a swinging contact is not lagged: the start force is
  // an end force of the last step, and friction from it held the incline's block 10 % harder.)
  if (c.shear_swings >= 2 && !energy_consistent_)
    normal_force = c.start_normal_force >= 0.0 ? c.start_normal_force
                                               : 0.5 * (normal_force + c.used_normal_force);
  c.used_normal_force = normal_force;
  return normal_force;
}

double ContactStage::shear_capacity(Contact& c, double normal_force, double elastic_force,
                                    double tolerance, bool& bond_broke) const {
  double capacity = c.friction * normal_force + (c.bonded ? c.cohesion * c.area : 0.0);
  bond_broke = false;
  if (c.bonded && std::abs(elastic_force) > capacity + tolerance) {
    // Sheared past its cohesion: the bond breaks and only friction is left.
    c.bonded = false;
    bond_broke = true;
    capacity = c.friction * normal_force;
  }
  return capacity;
}

ContactStage::ShearUpdate ContactStage::update_shear_with_inertia(Contact& c, double gap,
                                                                  double slip, double tolerance) {
  const double ks = rules_.parameters.shear_stiffness;
  const ContactState before = c.state;
  ShearUpdate out;
  // The shear force this solve assumed, at its result (none if it was open).
  out.assumed = before == ContactState::locked    ? ks * (c.shear_spring + slip)
                : before == ContactState::sliding ? -c.friction_force
                                                  : 0.0;
  if (before == ContactState::open) {
    // It closed in this solve, which did not resist its overlap: the normal force that overlap
    // stands for is no force the contact carried (deep, where the other contacts opened), and
    // friction from it, as a load in the next solve, threw the sliding block of
    // data/verification/frictional_incline.toml about at its release (2e4 to 5e4 N on single
    // contacts of a 7.5 kN block). It takes part in the next solve with its normal spring and
    // no friction; Coulomb's law applies from the normal force that solve gives it.
    c.state = ContactState::sliding;
    c.slip_sign = 0.0;
    c.friction_force = 0.0;
    return out;
  }
  const double normal_force = friction_normal_force(c, gap);
  // Coulomb's law as the return mapping of a rigid-plastic spring: the shear past the
  // anchor either fits within the capacity (locked) or the anchor follows the contact so
  // that the spring carries exactly the capacity (sliding, with no shear stiffness and the
  // friction as a load in the next solve).
  // The trial of a sliding contact starts from its anchor at the start of the step (or where
  // it closed in this step), as a return mapping over the step does, not from where the last
  // iterate left it: the friction opposes the step's slip. Taken from the last iterate, the
  // direction was that of the correction between two iterates, often opposite to the motion:
  // friction then pushed the block along, or a correction of a few nanometres read as
  // "slid back past its anchor" and locked a block moving at 1 m/s.
  if (before == ContactState::sliding) c.shear_spring = c.anchor_start;
  const double elastic = c.shear_spring + slip;
  const double capacity = shear_capacity(c, normal_force, ks * elastic, tolerance, out.bond_broke);
  // Within the capacity it holds. A sliding contact that slid back past its anchor under the
  // friction load holds too: friction was more than enough, so it sticks at its anchor, and
  // the next solve's spring finds the force that holds it there. Locked where the friction
  // load had pushed it, with that load kept in its spring, it pushed the vertex on along the
  // step's slip (docs/method-choices.md, "Energy at a landing").
  const bool within = ks * std::abs(elastic) <= capacity;
  const bool slid_back = before == ContactState::sliding && elastic * c.slip_sign < 0.0;
  if (capacity > 0.0 && (within || slid_back)) {
    c.state = ContactState::locked;
    out.implied = ks * elastic;
  } else {
    c.state = ContactState::sliding;
    c.slip_sign = elastic > 0.0 ? 1.0 : elastic < 0.0 ? -1.0 : 0.0;
    c.shear_spring = c.slip_sign * capacity / ks - slip;
    c.friction_force = -c.slip_sign * capacity;
    out.implied = -c.friction_force;
  }
  return out;
}

ContactStage::ShearUpdate ContactStage::update_shear_without_inertia(Contact& c, double gap,
                                                                     double slip,
                                                                     double tolerance) {
  const double ks = rules_.parameters.shear_stiffness;
  const ContactState before = c.state;
  ShearUpdate out;
  // The shear force the solve had at its result, from the spring of the contact's state: a
  // sliding contact carries the friction of the last iterate plus its sliding spring times
  // the slip since, a closing one the spring from where it touched.
  out.assumed = before == ContactState::sliding
                    ? -c.friction_force + c.slide_stiffness * (slip - c.slide_slip)
                    : ks * (c.shear_spring + slip);
  const double capacity =
      shear_capacity(c, friction_normal_force(c, gap), out.assumed, tolerance, out.bond_broke);
  if (before == ContactState::open || std::abs(out.assumed) <= capacity) {
    // A closing contact starts locked: its normal force so far is the overlap of a solve
    // without it, far more than it will carry, and friction from it would throw a fragment
    // that nothing else holds. A sliding contact back within the cone sticks where it is,
    // carrying the force it has.
    if (before == ContactState::sliding) c.shear_spring = out.assumed / ks - slip;
    c.state = ContactState::locked;
    c.slide_stiffness = rules_.parameters.sliding_stiffness;
    c.last_excess = 0.0;
    out.implied = out.assumed;
    return out;
  }
  const double sign = out.assumed > 0.0 ? 1.0 : -1.0;
  const double excess = std::abs(out.assumed) - capacity;
  // A contact that keeps sliding the same way and got less than halfway to its friction
  // limit is held back by its own spring more than by the rock around it (a fragment that
  // slides between open faces): its spring halves, down to kMinSlidingStiffness of the
  // first, so that it reaches the limit in a few iterations instead of hundreds.
  if (before == ContactState::sliding && sign == c.slip_sign && excess > 0.5 * c.last_excess &&
      excess > tolerance)
    c.slide_stiffness = std::max(0.5 * c.slide_stiffness,
                                 kMinSlidingStiffness * rules_.parameters.sliding_stiffness);
  c.last_excess = excess;
  c.state = ContactState::sliding;
  c.slip_sign = sign;
  c.friction_force = -sign * capacity;
  c.slide_slip = slip;
  c.shear_spring = sign * capacity / ks - slip;  // where it sticks, should it stop here
  out.implied = sign * capacity;
  return out;
}

namespace {

/// Normal and shear force of a closed contact at `gap` and step slip `slip` (commit's rule).
std::pair<double, double> spring_forces(const Contact& c, const ContactParameters& p, double gap,
                                        double slip) {
  const double shear = c.state == ContactState::locked
                           ? p.shear_stiffness * (c.shear_spring + slip)
                           : -c.friction_force + c.slide_stiffness * (slip - c.slide_slip);
  return {p.normal_stiffness * gap, shear};
}

}  // namespace

double ContactStage::spring_energy_at(std::span<const double> positions) const {
  double energy = 0.0;
  for (const Contact& c : contacts_) {
    if (c.state == ContactState::open) continue;
    const auto [normal, shear] =
        spring_forces(c, rules_.parameters, linear_gap(c, positions), step_slip(c, positions));
    energy += 0.5 * (normal * normal / rules_.parameters.normal_stiffness +
                     shear * shear / rules_.parameters.shear_stiffness);
  }
  return energy;
}

double ContactStage::friction_work_between(std::span<const double> from,
                                           std::span<const double> to) const {
  double work = 0.0;
  for (const Contact& c : contacts_)
    if (c.state == ContactState::sliding)
      work += std::abs(c.friction_force) * std::abs(step_slip(c, to) - step_slip(c, from));
  return work;
}

void ContactStage::add_committed_forces(std::span<const double> positions,
                                        std::span<double> force) const {
  for (const Contact& c : contacts_) {
    if (c.state == ContactState::open) continue;
    add_to_nodes(c, c.g, rules_.parameters.normal_stiffness * linear_gap(c, positions), force);
    const double shear =
        c.state == ContactState::locked
            ? rules_.parameters.shear_stiffness * c.shear_spring
            : -c.friction_force + c.slide_stiffness * (step_slip(c, positions) - c.slide_slip);
    add_to_nodes(c, c.t, shear, force);
  }
}

double ContactStage::commit(std::span<const double> positions, double& friction_work) {
  const double kn = rules_.parameters.normal_stiffness, ks = rules_.parameters.shear_stiffness;
  double spring_energy = 0.0;
  for (Contact& c : contacts_) {
    if (c.state == ContactState::open) {
      if (energy_consistent_ && c.closed_at_start) {
        friction_work += std::abs(c.friction_force) * std::abs(step_slip(c, positions));
        c.friction_force = 0.0;
      }
      c.shear_spring = 0.0;
      continue;
    }
    // Energy: the springs' elastic energy, and friction's work over the slip the anchor
    // followed in this step (plastic slip, from where it stood at the step start or closing).
    const double slip = step_slip(c, positions);
    c.end_gap = linear_gap(c, positions);
    const auto [normal, shear] = spring_forces(c, rules_.parameters, c.end_gap, slip);
    spring_energy += 0.5 * (normal * normal / kn + shear * shear / ks);
    friction_work += std::abs(shear) * std::abs(c.anchor_start - c.shear_spring);
    // The anchor is kept in the next step's slip coordinate, which starts from 0.
    c.shear_spring += slip;
    c.anchor_start = c.shear_spring;
  }
  started_ = true;
  return spring_energy;
}

}  // namespace rockdd

#include "engine/damage/fragment_restraint.hpp"

#include <Eigen/Dense>

#include <algorithm>

#include "engine/common/disjoint_sets.hpp"
#include "engine/model/edge_adjacency.hpp"

namespace rockdd {

namespace {

/// Parts: the elements that are not fully broken (w < 1), joined across the edges they share
/// (`edges`, the adjacency of model.conn). part[e] numbers them in element order; -1 for a
/// broken element.
std::vector<std::int32_t> intact_parts(const Model& model, const EdgeAdjacency& edges,
                                       std::int32_t& num_parts) {
  const auto num_elements = static_cast<std::size_t>(model.num_elements());
  DisjointSets parts(num_elements);
  const auto intact = [&](std::int32_t e) { return model.damage[e] < 1.0; };
  for (std::size_t e = 0; e < num_elements; ++e) {
    if (!intact(static_cast<std::int32_t>(e))) continue;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t other = edges.neighbor[3 * e + k];
      if (other <= static_cast<std::int32_t>(e) || !intact(other)) continue;
      parts.join(static_cast<std::int32_t>(e), other);
    }
  }
  std::vector<std::int32_t> part(num_elements, -1);
  num_parts = 0;
  for (std::size_t e = 0; e < num_elements; ++e) {
    if (!intact(static_cast<std::int32_t>(e))) continue;
    const std::int32_t r = parts.find(static_cast<std::int32_t>(e));
    if (part[r] < 0) part[r] = num_parts++;
    part[e] = part[r];
  }
  return part;
}

/// Each node's parts, in node order (a node is in every part one of its intact elements is in).
std::vector<GroupNode> part_members(const NodeIncidence& incidence,
                                    std::span<const std::int32_t> part, std::int32_t num_nodes) {
  std::vector<GroupNode> members;
  members.reserve(static_cast<std::size_t>(num_nodes));
  for (std::int32_t n = 0; n < num_nodes; ++n) {
    const std::size_t first = members.size();
    for (std::int32_t i = incidence.offset[n]; i < incidence.offset[n + 1]; ++i) {
      const std::int32_t p = part[incidence.element[i]];
      if (p < 0) continue;
      bool seen = false;
      for (std::size_t m = first; m < members.size(); ++m) seen = seen || members[m].group == p;
      if (!seen) members.push_back({p, n});
    }
  }
  return members;
}

/// Adds to k (per dof) a statically determinate support of part p: springs on as few of its
/// free dofs as hold the rigid modes that its prescribed dofs and held nodes leave free, each
/// chosen greedily as the dof most aligned with the slowest mode left (lowest dof on a tie).
/// A determinate support carries no force while the part's loads balance, so it holds the
/// part's position without stiffening its deformation.
void hold_rigid_modes(const Model& model, const BoundaryConditions& bc,
                      std::span<const std::uint8_t> held, std::span<const GroupNode> members,
                      std::span<const std::int32_t> part, std::int32_t p, double support,
                      std::vector<double>& k) {
  std::vector<std::int32_t> nodes;
  for (const auto& [q, n] : members)
    if (q == p) nodes.push_back(n);
  const auto position = [&](std::int32_t n) {
    return Eigen::Vector2d(model.X[2 * static_cast<std::size_t>(n)],
                           model.X[2 * static_cast<std::size_t>(n) + 1]);
  };
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const std::int32_t n : nodes) centroid += position(n);
  centroid /= static_cast<double>(nodes.size());
  double size = 0.0;
  for (const std::int32_t n : nodes) size = std::max(size, (position(n) - centroid).norm());
  size = std::max(size, 1e-300);
  const auto row = [&](std::int32_t n, int c) {
    const Eigen::Vector2d r = (position(n) - centroid) / size;
    return c == 0 ? Eigen::Vector3d(1, 0, -r.y()) : Eigen::Vector3d(0, 1, r.x());
  };
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  for (const std::int32_t n : nodes)
    for (int c = 0; c < 2; ++c)
      if (bc.prescribed[2 * static_cast<std::size_t>(n) + c] || held[n])
        g += row(n, c) * row(n, c).transpose();
  double young = 0.0, count = 0.0;
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    if (part[e] == p) {
      young += model.young[e];
      count += 1.0;
    }
  const double stiffness = support * young / std::max(count, 1.0) * model.thickness;
  for (int added = 0; added < 3; ++added) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(g);
    if (eig.eigenvalues()(0) > 1e-10) return;
    const Eigen::Vector3d mode = eig.eigenvectors().col(0);
    double best = 0.0;
    std::int32_t best_node = -1;
    int best_c = 0;
    for (const std::int32_t n : nodes)
      for (int c = 0; c < 2; ++c) {
        if (bc.prescribed[2 * static_cast<std::size_t>(n) + c] || held[n]) continue;
        const double a = std::abs(row(n, c).dot(mode));
        if (a > best * (1.0 + 1e-12)) {
          best = a;
          best_node = n;
          best_c = c;
        }
      }
    if (best_node < 0) return;
    g += row(best_node, best_c) * row(best_node, best_c).transpose();
    k[2 * static_cast<std::size_t>(best_node) + best_c] += stiffness;
  }
}

}  // namespace

FragmentRestraint::FragmentRestraint(const Model& model, const BoundaryConditions& bc,
                                     double fraction, double support)
    : FragmentRestraint(model, build_edge_adjacency(model.conn, "restraint"), bc, fraction,
                        support) {}

FragmentRestraint::FragmentRestraint(const Model& model, const EdgeAdjacency& edges,
                                     const BoundaryConditions& bc, double fraction,
                                     double support) {
  const NodeIncidence incidence = build_node_incidence(model.conn, model.num_nodes());
  std::int32_t num_parts = 0;
  const std::vector<std::int32_t> part = intact_parts(model, edges, num_parts);
  const std::vector<GroupNode> members = part_members(incidence, part, model.num_nodes());
  const auto num_nodes = static_cast<std::size_t>(model.num_nodes());
  // Held parts and nodes: a part the prescribed dofs hold, then, until nothing changes, a part
  // pinned to held nodes (a node of a held part moves with it) so that its modes are held.
  std::vector<std::uint8_t> free = unrestrained_groups(model, bc, members, num_parts);
  std::vector<std::uint8_t> held(num_nodes, 0);
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& [p, n] : members)
      if (!free[p] && !held[n]) held[n] = grew = true;
    // Only a free part with a held node can be pinned by it.
    const bool hinged = std::any_of(members.begin(), members.end(), [&](const GroupNode& m) {
      return free[m.group] && held[m.node];
    });
    if (!grew || !hinged) break;
    BoundaryConditions pinned = bc;
    for (std::size_t n = 0; n < num_nodes; ++n)
      if (held[n]) pinned.prescribed[2 * n] = pinned.prescribed[2 * n + 1] = 1;
    const std::vector<std::uint8_t> still = unrestrained_groups(model, pinned, members, num_parts);
    for (std::int32_t p = 0; p < num_parts; ++p) free[p] = free[p] && still[p];
  }
  // A free part of a block that a boundary holds was cut loose inside this step (elements broke
  // around it but are not detached yet): it gets a support that holds only its free rigid
  // modes. The other free parts (blocks detached loose) and lone nodes (only broken elements
  // touch them) get the weak spring on every node.
  std::vector<std::uint8_t> cut_loose(static_cast<std::size_t>(num_parts), 0),
      in_part(num_nodes, 0);
  if (std::find(free.begin(), free.end(), 1) != free.end()) {
    const std::vector<std::uint8_t> block_free = unrestrained_blocks(model, bc);
    for (std::int32_t e = 0; e < model.num_elements(); ++e)
      if (part[e] >= 0 && free[part[e]] && !block_free[model.element_block[e]])
        cut_loose[part[e]] = 1;
  }
  for (const auto& [p, n] : members) in_part[n] = 1;
  std::vector<double> k(2 * num_nodes, 0.0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) {
    if (part[e] >= 0 && cut_loose[part[e]]) continue;
    // Like a lumped mass: each corner takes a third of the element's share.
    const double share = fraction * model.young[e] * model.thickness / 3.0;
    for (int c = 0; c < 3; ++c) {
      const auto n = static_cast<std::size_t>(model.conn[3 * static_cast<std::size_t>(e) + c]);
      if (held[n] || (!in_part[n] && bc.prescribed[2 * n] && bc.prescribed[2 * n + 1])) continue;
      if (part[e] < 0 && in_part[n]) continue;  // a broken element's corner on a part
      k[2 * n] += share;
      k[2 * n + 1] += share;
    }
  }
  for (std::int32_t p = 0; p < num_parts; ++p)
    if (cut_loose[p]) hold_rigid_modes(model, bc, held, members, part, p, support, k);
  for (std::size_t d = 0; d < k.size(); ++d)
    if (k[d] > 0.0) {
      dofs_.push_back(static_cast<std::int32_t>(d));
      stiffness_.push_back(k[d]);
    }
}

void FragmentRestraint::forces(std::span<const double> du, std::span<double> force) const {
  std::fill(force.begin(), force.end(), 0.0);
  for (std::size_t i = 0; i < dofs_.size(); ++i)
    force[dofs_[i]] = stiffness_[i] * (du[dofs_[i]] - anchor(i));
}

double FragmentRestraint::energy(std::span<const double> du) const {
  double energy = 0.0;
  for (std::size_t i = 0; i < dofs_.size(); ++i) {
    const double x = du[dofs_[i]] - anchor(i);
    energy += 0.5 * stiffness_[i] * x * x;
  }
  return energy;
}

void FragmentRestraint::anchor_new_springs(const FragmentRestraint& before,
                                           std::span<const double> du) {
  anchor_.assign(dofs_.size(), 0.0);
  std::size_t j = 0;
  for (std::size_t i = 0; i < dofs_.size(); ++i) {
    while (j < before.dofs_.size() && before.dofs_[j] < dofs_[i]) ++j;
    anchor_[i] = j < before.dofs_.size() && before.dofs_[j] == dofs_[i] &&
                         before.stiffness_[j] == stiffness_[i]
                     ? before.anchor(j)
                     : du[dofs_[i]];
  }
}

void FragmentRestraint::follow(std::span<const double> du) {
  anchor_.resize(dofs_.size());
  for (std::size_t i = 0; i < dofs_.size(); ++i) anchor_[i] = du[dofs_[i]];
}

}  // namespace rockdd

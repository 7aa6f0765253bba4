#include "engine/loading/boundary_conditions.hpp"

#include <Eigen/Dense>

#include <span>
#include <string>

#include "engine/common/errors.hpp"
#include "engine/loading/named_nodes.hpp"

namespace rockdd {

BoundaryConditions build_boundary_conditions(const Scene& scene, const Model& model) {
  const std::size_t num_dofs = model.X.size();
  BoundaryConditions bc;
  bc.prescribed.assign(num_dofs, 0);
  bc.velocity.assign(num_dofs, 0.0);
  for (std::size_t i = 0; i < scene.boundaries.size(); ++i) {
    const BoundarySpec& b = scene.boundaries[i];
    const auto nodes =
        nodes_named(model, b.on, scene.file.string(), "boundary[" + std::to_string(i) + "].on");
    for (const std::int32_t n : nodes) {
      const bool fix[2] = {b.fix_x, b.fix_y};
      const std::optional<double> vel[2] = {b.velocity_x, b.velocity_y};
      for (int c = 0; c < 2; ++c) {
        if (!fix[c] && !vel[c]) continue;
        bc.prescribed[2 * n + c] = 1;
        bc.velocity[2 * n + c] = vel[c].value_or(0.0);
      }
    }
  }
  bc.equation.assign(num_dofs, -1);
  for (std::size_t d = 0; d < num_dofs; ++d)
    if (!bc.prescribed[d]) bc.equation[d] = bc.num_equations++;
  return bc;
}

namespace {

/// Per group, G = sum over the prescribed dofs of its nodes of r r^T with r the dof's value in
/// the three rigid modes (x translation, y translation, rotation about the group's centroid,
/// lengths scaled by the group's size). The group is held exactly when G is regular.
/// `members` lists (group, node) pairs, each once; a node may belong to several groups.
std::vector<Eigen::Matrix3d> restraint_gram(const Model& model, const BoundaryConditions& bc,
                                            std::span<const GroupNode> members,
                                            std::int32_t num_groups) {
  const auto groups = static_cast<std::size_t>(num_groups);
  std::vector<Eigen::Vector2d> centroid(groups, Eigen::Vector2d::Zero());
  std::vector<double> count(groups, 0.0), size(groups, 0.0);
  const auto position = [&](std::int32_t n) {
    return Eigen::Vector2d(model.X[2 * static_cast<std::size_t>(n)],
                           model.X[2 * static_cast<std::size_t>(n) + 1]);
  };
  for (const auto& [b, n] : members) {
    centroid[b] += position(n);
    count[b] += 1.0;
  }
  for (std::size_t b = 0; b < groups; ++b) centroid[b] /= std::max(count[b], 1.0);
  for (const auto& [b, n] : members)
    size[b] = std::max(size[b], (position(n) - centroid[b]).norm());
  std::vector<Eigen::Matrix3d> g(groups, Eigen::Matrix3d::Zero());
  for (const auto& [b, n] : members) {
    const double L = std::max(size[b], 1e-300);
    const Eigen::Vector2d r = (position(n) - centroid[b]) / L;
    if (bc.prescribed[2 * static_cast<std::size_t>(n)]) {
      Eigen::Vector3d mode(1, 0, -r.y());
      g[b] += mode * mode.transpose();
    }
    if (bc.prescribed[2 * static_cast<std::size_t>(n) + 1]) {
      Eigen::Vector3d mode(0, 1, r.x());
      g[b] += mode * mode.transpose();
    }
  }
  return g;
}

std::vector<Eigen::Matrix3d> restraint_gram(const Model& model, const BoundaryConditions& bc) {
  std::vector<GroupNode> members(static_cast<std::size_t>(model.num_nodes()));
  for (std::int32_t n = 0; n < model.num_nodes(); ++n) members[n] = {model.node_block[n], n};
  return restraint_gram(model, bc, members, model.num_blocks);
}

/// The slowest rigid mode of a Gram matrix, and whether the constraints miss it.
bool misses_a_mode(const Eigen::Matrix3d& g, Eigen::Vector3d* mode = nullptr) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(g);
  if (mode) *mode = eig.eigenvectors().col(0);
  return eig.eigenvalues()(0) <= 1e-10;
}

}  // namespace

std::vector<std::uint8_t> unrestrained_blocks(const Model& model, const BoundaryConditions& bc) {
  const std::vector<Eigen::Matrix3d> g = restraint_gram(model, bc);
  std::vector<std::uint8_t> free(g.size(), 0);
  for (std::size_t b = 0; b < g.size(); ++b) free[b] = misses_a_mode(g[b]) ? 1 : 0;
  return free;
}

std::vector<std::uint8_t> unrestrained_groups(const Model& model, const BoundaryConditions& bc,
                                              std::span<const GroupNode> members,
                                              std::int32_t num_groups) {
  const std::vector<Eigen::Matrix3d> g = restraint_gram(model, bc, members, num_groups);
  std::vector<std::uint8_t> free(g.size(), 0);
  for (std::size_t b = 0; b < g.size(); ++b) free[b] = misses_a_mode(g[b]) ? 1 : 0;
  return free;
}

std::optional<FreeBlock> find_free_block(const Model& model, const BoundaryConditions& bc,
                                         std::int32_t min_elements) {
  const std::vector<Eigen::Matrix3d> g = restraint_gram(model, bc);
  const std::size_t num_blocks = g.size();
  std::vector<std::int32_t> elements(num_blocks, 0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) ++elements[model.element_block[e]];
  for (std::size_t b = 0; b < num_blocks; ++b) {
    Eigen::Vector3d mode;
    if (elements[b] < min_elements || !misses_a_mode(g[b], &mode)) continue;
    FreeBlock free{static_cast<std::int32_t>(b), elements[b], "",
                   std::abs(mode(2)) > 0.5                  ? "rotation"
                   : std::abs(mode(0)) >= std::abs(mode(1)) ? "x translation"
                                                            : "y translation"};
    for (std::int32_t e = 0; e < model.num_elements(); ++e)
      if (model.element_block[e] == free.block) {
        free.body = model.sets.bodies[model.element_body[e]];
        break;
      }
    return free;
  }
  return std::nullopt;
}

void check_static_restraint(const Scene& scene, const Model& model, const BoundaryConditions& bc) {
  const std::optional<FreeBlock> free = find_free_block(model, bc);
  if (!free) return;
  throw InputError(scene.file.string(), "boundary",
                   "static analysis needs every block restrained, but block " +
                       std::to_string(free->block) + " (body '" + free->body + "') is free in " +
                       free->motion +
                       ": add [[boundary]] constraints or use analysis = \"quasi-static\"");
}

}  // namespace rockdd

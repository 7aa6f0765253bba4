#include "engine/time/rotation_correction.hpp"

#include <cmath>
#include <vector>

namespace rockdd {
namespace {

/// Mass-weighted block sums of a 2-per-node field: sum m f, per block.
void block_sums(const Model& model, std::span<const double> field, std::vector<double>& sx,
                std::vector<double>& sy) {
  sx.assign(static_cast<std::size_t>(model.num_blocks), 0.0);
  sy.assign(static_cast<std::size_t>(model.num_blocks), 0.0);
  for (std::int32_t n = 0; n < model.num_nodes(); ++n) {
    const auto b = static_cast<std::size_t>(model.node_block[n]);
    sx[b] += model.node_mass[n] * field[2 * n];
    sy[b] += model.node_mass[n] * field[2 * n + 1];
  }
}

/// f_n <- mean + R (f_n - mean) for the nodes of turned blocks.
void turn_about_mean(const Model& model, const std::vector<double>& theta,
                     const std::vector<double>& mass, std::span<double> field) {
  std::vector<double> sx, sy;
  block_sums(model, field, sx, sy);
  for (std::int32_t n = 0; n < model.num_nodes(); ++n) {
    const auto b = static_cast<std::size_t>(model.node_block[n]);
    if (theta[b] == 0.0) continue;
    const double mx = sx[b] / mass[b], my = sy[b] / mass[b];
    const double fx = field[2 * n] - mx, fy = field[2 * n + 1] - my;
    const double cs = std::cos(theta[b]), sn = std::sin(theta[b]);
    field[2 * n] = mx + cs * fx - sn * fy;
    field[2 * n + 1] = my + sn * fx + cs * fy;
  }
}

}  // namespace

void correct_block_rotations(const Model& model, std::span<const double> u,
                             std::span<const std::uint8_t> held_nodes, std::span<double> du,
                             std::span<double> v, std::span<double> acceleration) {
  const auto num_blocks = static_cast<std::size_t>(model.num_blocks);
  const std::int32_t num_nodes = model.num_nodes();
  std::vector<double> mass(num_blocks, 0.0);
  std::vector<std::uint8_t> held(num_blocks, 0);
  for (std::int32_t n = 0; n < num_nodes; ++n) {
    const auto b = static_cast<std::size_t>(model.node_block[n]);
    mass[b] += model.node_mass[n];
    if (held_nodes[n]) held[b] = 1;
  }
  std::vector<double> position(u.size());
  for (std::size_t d = 0; d < u.size(); ++d) position[d] = model.X[d] + u[d];
  std::vector<double> cx, cy;
  block_sums(model, position, cx, cy);
  // theta_b = sum m (r x du) / sum m |r|^2: the least-squares rotation of the increment.
  std::vector<double> moment(num_blocks, 0.0), inertia(num_blocks, 0.0);
  for (std::int32_t n = 0; n < num_nodes; ++n) {
    const auto b = static_cast<std::size_t>(model.node_block[n]);
    const double rx = position[2 * n] - cx[b] / mass[b];
    const double ry = position[2 * n + 1] - cy[b] / mass[b];
    const double m = model.node_mass[n];
    moment[b] += m * (rx * du[2 * n + 1] - ry * du[2 * n]);
    inertia[b] += m * (rx * rx + ry * ry);
  }
  std::vector<double> theta(num_blocks, 0.0);
  for (std::size_t b = 0; b < num_blocks; ++b)
    if (!held[b] && inertia[b] > 0.0) theta[b] = moment[b] / inertia[b];
  for (std::int32_t n = 0; n < num_nodes; ++n) {
    const auto b = static_cast<std::size_t>(model.node_block[n]);
    if (theta[b] == 0.0) continue;
    const double rx = position[2 * n] - cx[b] / mass[b];
    const double ry = position[2 * n + 1] - cy[b] / mass[b];
    const double cs = std::cos(theta[b]), sn = std::sin(theta[b]);
    // Exact rotation of r minus its linear part theta J r, J r = (-ry, rx).
    du[2 * n] += (cs - 1.0) * rx - sn * ry + theta[b] * ry;
    du[2 * n + 1] += sn * rx + (cs - 1.0) * ry - theta[b] * rx;
  }
  turn_about_mean(model, theta, mass, v);
  turn_about_mean(model, theta, mass, acceleration);
}

}  // namespace rockdd

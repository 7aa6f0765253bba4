#pragma once
// DDA's step moves every point along a straight line, du = v dt + ...: a block that turns by
// theta in a step is stretched radially by theta^2 / 2, and the elastic energy of that
// stretch feeds back into the motion; its velocity update 2 du / dt - v also grows the speed
// of a turning block by theta^2 / 6. A freely spinning block would gain 3 % of its energy in
// three turns at omega dt = 5e-3. The correction turns each free block's increment and
// velocity by the block's rotation in the step, exactly. A block that a constraint or a closed
// contact holds is left alone: its increment is what the solve balanced against those
// contacts, and turning it afterwards moved a collapsing block of a compression specimen by
// theta^2 r / 2 = 3 um into its neighbours (theta = 0.01 rad in one quasi-static step), which
// the penalty springs then held as 70 J against 11 J of work (issue 11).
#include <cstdint>
#include <span>

#include "engine/model/model.hpp"

namespace rockdd {

/// For each block none of whose nodes is `held` (1 per node: prescribed, or in a closed
/// contact): theta_b, its mass-weighted rotation increment in
/// the straight-line `du` (from displacement `u`), is applied exactly: du += (R - I) r -
/// theta_b J r, r the node's position about the block's centre of mass; the velocity `v` and
/// `acceleration` (already updated from the straight-line du) are turned by R about the
/// block's mean. Mass centre, momentum and kinetic energy are unchanged. Deterministic.
void correct_block_rotations(const Model& model, std::span<const double> u,
                             std::span<const std::uint8_t> held, std::span<double> du,
                             std::span<double> v, std::span<double> acceleration);

}  // namespace rockdd

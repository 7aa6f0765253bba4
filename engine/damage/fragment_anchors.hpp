#pragma once
// Fragments in steps without inertia. A one-element block that fracture cut out is held
// only by its contacts, and with no mass term a contact force it does not balance would throw
// it. Each fragment is tied, by a spring on each corner, to the copy of that corner in one
// neighbouring block (its partner): the spring resists only their motion relative to each
// other within a step, so the fragment follows the rock around it and adds no stiffness to
// the specimen's own deformation. A corner with no copy in the partner block is tied weakly
// to where the step started, so that the system stays positive definite.
#include <cstdint>
#include <vector>

#include "engine/model/model.hpp"

namespace rockdd {

/// A spring between a fragment's corner and its partner node, or to the step start.
struct AnchorSpring {
  std::int32_t node = -1;     // a corner of a fragment
  std::int32_t partner = -1;  // its copy in the partner block, or -1: tied to the step start
  double stiffness = 0.0;     // N/m, to the partner's (or the step start's) motion in the step
};

/// The springs of every fragment of `model`: stiffness `relative` x E0 t to the partner,
/// `absolute` x E0 t to the step start where a corner has no partner. The partner block is
/// the neighbouring block holding copies of most of the fragment's corners, blocks of more than
/// one element first, then the lowest block id. Deterministic, in fragment order.
std::vector<AnchorSpring> anchor_fragments(const Model& model, double relative, double absolute);

}  // namespace rockdd

#pragma once
// [[initial]]: the rigid motion a body starts with.
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Sets model.v on the nodes of each [[initial]] body to its rigid motion
/// v = v0 + omega x (x - centroid), the centroid of its lumped mass. Throws InputError for a
/// body the model does not have.
void apply_initial_motion(const Scene& scene, Model& model);

}  // namespace rockdd

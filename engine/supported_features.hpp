#pragma once
// Scene features that the parser accepts but the engine does not run yet.
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Throws InputError ("... is not supported yet") naming the first such key in the scene.
void check_supported_features(const Scene& scene);

}  // namespace rockdd

#pragma once
// What a rockdd::api::Scene holds: the engine's validated Scene.
#include "engine/scene/scene.hpp"
#include "rockdd/rockdd.hpp"

namespace rockdd::api {

struct Scene::Impl {
  rockdd::Scene scene;
};

/// The engine's scene behind a handle (for the API's other files).
struct SceneAccess {
  static const rockdd::Scene& scene(const Scene& s) { return s.impl_->scene; }
};

}  // namespace rockdd::api

#include "engine/supported_features.hpp"

namespace rockdd {

void check_supported_features(const Scene& scene) {
  // Every key of SCENE.md is implemented. This is where a key that the reader accepts but
  // the engine cannot honour yet is rejected with InputError naming it, so that no scene
  // runs with a setting silently ignored.
  static_cast<void>(scene);
}

}  // namespace rockdd

#pragma once
// Looking up the nodes of a named curve or point, with errors that name the scene key.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/model/model.hpp"

namespace rockdd {

/// Sorted unique nodes of the physical curve or point `name`. Throws InputError naming
/// `key` (e.g. "boundary[0].on") and the available names when there is none.
std::vector<std::int32_t> nodes_named(const Model& model, const std::string& name,
                                      const std::string& scene_file, const std::string& key);

/// Index of body `name` in model.sets.bodies ("*" = -1 meaning every body); InputError if unknown.
std::int32_t body_named(const Model& model, const std::string& name, const std::string& scene_file,
                        const std::string& key);

}  // namespace rockdd

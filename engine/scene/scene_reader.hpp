#pragma once
// Reading a scene: TOML text → overrides applied → every key validated → Scene.
// The schema is docs/scene.md; any violation is an InputError (exit status 2).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// Reads and validates the scene file `file`, after applying the `--set key.path=value`
/// `overrides`. Throws InputError (file:line, key path, expected/got) on any bad input.
Scene read_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

/// As read_scene, from `text`; `file` names the scene in errors and anchors relative paths.
Scene parse_scene(std::string_view text, const std::filesystem::path& file,
                  const std::vector<std::string>& overrides = {});

}  // namespace rockdd

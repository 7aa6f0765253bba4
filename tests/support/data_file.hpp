#pragma once
// Paths of the repository's data/ folder (the reference scenes and their meshes).
#include <filesystem>
#include <string>

namespace rockdd::test {

/// A file of data/ (a scene, a .geo), by its path inside data/.
inline std::filesystem::path data_file(const std::string& name) {
  return std::filesystem::path(ROCKDD_SOURCE_DIR) / "data" / name;
}

}  // namespace rockdd::test

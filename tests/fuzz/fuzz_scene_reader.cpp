// libFuzzer harness: the fuzz input is a scene file's text (docs/stability.md, Fuzzing).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "fuzz_scene_check.hpp"

namespace {

// In the folder of the good scenes, so that relative mesh.geo paths of the seeds resolve.
const std::filesystem::path kSceneFile =
    std::filesystem::path(ROCKDD_SOURCE_DIR) / "tests/scenes/good/fuzz_input.toml";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rockdd::fuzz::check_scene(text, kSceneFile);
  return 0;
}

// libFuzzer harness: each line of the fuzz input is one `--set key.path=value`, applied to
// tests/scenes/good/minimal_static.toml (a rectangle, so accepted overrides get meshed).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_scene_check.hpp"

namespace {

const std::filesystem::path kBaseScene =
    std::filesystem::path(ROCKDD_SOURCE_DIR) / "tests/scenes/good/minimal_static.toml";

const std::string& base_text() {
  static const std::string text = [] {
    std::ifstream in(kBaseScene, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
  }();
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> overrides;
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string line; std::getline(lines, line);) overrides.push_back(line);
  rockdd::fuzz::check_scene(base_text(), kBaseScene, overrides);
  return 0;
}

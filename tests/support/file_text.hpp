#pragma once
// Reading a whole file as text.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace rockdd::test {

/// The whole content of a file.
inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace rockdd::test

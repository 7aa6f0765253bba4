#include "engine/mesh/msh_physical_names.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>

namespace rockdd {

namespace {

/// `line` without the trailing spaces, tabs and '\r' of a file written on Windows.
std::string_view trimmed(std::string_view line) {
  const auto last = line.find_last_not_of(" \t\r");
  return line.substr(0, last == std::string_view::npos ? 0 : last + 1);
}

/// True for "<dim> <tag> \"<name>\"": dim 0..3, tag >= 1, name printable and closed.
bool valid_entry(std::string_view line) {
  std::istringstream fields{std::string(line)};
  long dim = -1, tag = 0;
  if (!(fields >> dim >> tag) || dim < 0 || dim > 3 || tag < 1) return false;
  std::string rest;
  std::getline(fields, rest);
  const std::size_t first = rest.find_first_not_of(" \t");
  const std::string_view name =
      trimmed(std::string_view(rest).substr(std::min(first, rest.size())));
  if (name.size() < 2 || name.front() != '"' || name.back() != '"') return false;
  for (const char c : name.substr(1, name.size() - 2))
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f || c == '"')
      return false;
  return true;
}

}  // namespace

// Found by fuzzing (tests/fuzz): Gmsh indexes its per-dimension tables by the dimension it
// reads here without checking it, so a name of dimension 4 crashed it (SIGSEGV) in
// GModel::setPhysicalName.
void check_msh_physical_names(const std::filesystem::path& file, const MeshSource& source) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string in_file = " (in " + file.string() + ")";
  constexpr std::string_view kStart = "$PhysicalNames", kEnd = "$EndPhysicalNames";
  for (std::size_t at = bytes.find(kStart); at != std::string::npos;
       at = bytes.find(kStart, at + kStart.size())) {
    if (at > 0 && bytes[at - 1] != '\n') continue;  // not at the start of a line
    std::istringstream lines(bytes.substr(at, bytes.find(kEnd, at) == std::string::npos
                                                  ? std::string::npos
                                                  : bytes.find(kEnd, at) - at + kEnd.size()));
    std::string line;
    std::getline(lines, line);
    long count = -1;
    std::getline(lines, line);
    std::istringstream(line) >> count;
    if (count < 0)
      source.fail("expected the number of physical names after $PhysicalNames, got \"" +
                  std::string(trimmed(line)).substr(0, 40) + "\"" + in_file);
    for (long i = 0; i < count; ++i) {
      if (!std::getline(lines, line) || trimmed(line) == kEnd)
        source.fail("expected " + std::to_string(count) + " physical names, found " +
                    std::to_string(i) + in_file);
      if (!valid_entry(trimmed(line)))
        source.fail(
            "expected a physical name as <dim 0-3> <tag >= 1> \"<printable name>\", got "
            "entry " +
            std::to_string(i + 1) + " of $PhysicalNames" + in_file);
    }
    if (!std::getline(lines, line) || trimmed(line) != kEnd)
      source.fail("expected $EndPhysicalNames after " + std::to_string(count) + " physical names" +
                  in_file);
  }
}

}  // namespace rockdd

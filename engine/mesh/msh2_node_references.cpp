#include "engine/mesh/msh2_node_references.hpp"

#include <fstream>
#include <sstream>
#include <string>
#include <unordered_set>

namespace rockdd {

namespace {

/// `line` without trailing spaces, tabs and the '\r' of a file written on Windows.
std::string trimmed(std::string line) {
  const auto last = line.find_last_not_of(" \t\r");
  line.erase(last == std::string::npos ? 0 : last + 1);
  return line;
}

}  // namespace

// Found by fuzzing (tests/fuzz): Gmsh 4.8's format-2 reader reads the number of nodes $Nodes
// declares and then dereferences a null node for an element that names any other tag, so a
// one-digit typo in a count or a tag crashed rockdd with a segmentation fault.
void check_msh2_node_references(const std::filesystem::path& file, const MeshSource& source) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  std::getline(in, line);  // $MeshFormat
  std::getline(in, line);
  std::istringstream header(line);
  double version = 0.0;
  int file_type = -1;
  header >> version >> file_type;
  if (!(version >= 2.0 && version < 3.0) || file_type != 0) return;

  std::unordered_set<long long> nodes;
  long long declared = -1;
  while (std::getline(in, line)) {
    const std::string section = trimmed(line);
    if (section == "$Nodes") {
      if (!std::getline(in, line) || !(std::istringstream(line) >> declared) || declared < 0)
        return;  // Gmsh reports an unreadable count
      for (long long n = 0; n < declared && std::getline(in, line); ++n) {
        long long tag = 0;
        if (std::istringstream(line) >> tag) nodes.insert(tag);
      }
    } else if (section == "$Elements") {
      long long count = 0;
      if (!std::getline(in, line) || !(std::istringstream(line) >> count)) return;
      for (long long e = 0; e < count && std::getline(in, line); ++e) {
        std::istringstream fields(line);
        long long tag = 0, node = 0;
        int type = 0, tags = 0;
        if (!(fields >> tag >> type >> tags) || tags < 0) return;
        for (int t = 0; t < tags; ++t) fields >> node;  // physical and entity tags
        while (fields >> node) {
          if (nodes.count(node)) continue;
          source.fail("expected elements whose nodes are among the " +
                      std::to_string(nodes.size()) + " of $Nodes, got element " +
                      std::to_string(tag) + " with node " + std::to_string(node) + " (in " +
                      file.string() + ")");
        }
      }
      return;
    }
  }
}

}  // namespace rockdd

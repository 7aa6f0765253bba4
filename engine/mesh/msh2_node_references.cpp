#include "engine/mesh/msh2_node_references.hpp"

#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <string>
#include <unordered_set>

namespace rockdd {

namespace {

/// Nodes of a format-2 element type (Gmsh's MElement::getInfoMSH for types 1-31), 0 if unknown.
int nodes_of_type(int type) {
  static constexpr int kNodes[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                                   8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  return type > 0 && type < static_cast<int>(std::size(kNodes)) ? kNodes[type] : 0;
}

}  // namespace

// Found by fuzzing (tests/fuzz): Gmsh 4.8's format-2 reader dereferences a null node for an
// element that names a node tag $Nodes did not define, so a one-digit typo in a count or a
// tag crashed rockdd with a segmentation fault. The file is read here as Gmsh reads it (fscanf
// of numbers, ignoring line breaks: "09 0.5 0.5 0" split over a line defines other tags than
// it seems to), so the check sees the tags Gmsh will see.
void check_msh2_node_references(const std::filesystem::path& file, const MeshSource& source) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> fp(std::fopen(file.c_str(), "rb"),
                                                           &std::fclose);
  if (!fp) return;  // Gmsh reports an unreadable file
  char line[256];
  double version = 0.0;
  int file_type = -1, data_size = 0;
  if (!std::fgets(line, sizeof line, fp.get()) ||
      std::fscanf(fp.get(), "%lf %d %d", &version, &file_type, &data_size) != 3 ||
      !(version >= 2.0 && version < 3.0) || file_type != 0)
    return;

  std::unordered_set<int> nodes;
  while (std::fgets(line, sizeof line, fp.get())) {
    if (std::strncmp(line, "$Nodes", 6) == 0) {
      int count = 0;
      if (std::fscanf(fp.get(), "%d", &count) != 1) return;
      for (int n = 0; n < count; ++n) {
        int tag = 0;
        double x, y, z;
        if (std::fscanf(fp.get(), "%d %lf %lf %lf", &tag, &x, &y, &z) != 4) return;
        nodes.insert(tag);
      }
    } else if (std::strncmp(line, "$Elements", 9) == 0) {
      int count = 0;
      if (std::fscanf(fp.get(), "%d", &count) != 1) return;
      for (int e = 0; e < count; ++e) {
        int tag = 0, type = 0, tags = 0, value = 0;
        if (std::fscanf(fp.get(), "%d %d %d", &tag, &type, &tags) != 3 || tags < 0) return;
        // Physical and entity tags, then (format 2.2) a partition count, the partitions and
        // further tags. Gmsh 4.8 crashes on partition lists and extra tags of format 2 (an
        // assertion, an invalid free, a segmentation fault: found by fuzzing), and rockdd
        // reads no partitioned mesh: at most a third tag, a partition count of 0.
        for (int t = 0; t < tags; ++t) {
          if (std::fscanf(fp.get(), "%d", &value) != 1) return;
          if (t == 3 || (t == 2 && value != 0))
            source.fail(
                "expected at most 3 tags per element (physical, elementary, and a "
                "partition count of 0: rockdd reads no partitioned mesh), got element " +
                std::to_string(tag) + " with " + std::to_string(tags) + " tags (in " +
                file.string() + ")");
        }
        const int corners = nodes_of_type(type);
        if (corners == 0) return;  // Gmsh reports the type
        for (int c = 0; c < corners; ++c) {
          if (std::fscanf(fp.get(), "%d", &value) != 1) return;
          if (nodes.count(value)) continue;
          source.fail("expected elements whose nodes are among the " +
                      std::to_string(nodes.size()) + " of $Nodes, got element " +
                      std::to_string(tag) + " with node " + std::to_string(value) + " (in " +
                      file.string() + ")");
        }
      }
      return;
    }
  }
}

}  // namespace rockdd

#include "engine/mesh/msh2_node_references.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <unordered_set>

#include "engine/mesh/msh_element_types.hpp"
#include "engine/scene/mesh_budget.hpp"

namespace rockdd {

namespace {

/// The memory budget of a file of `nodes` and `elements`, from its counts, before Gmsh reads
/// it: every element counts as a triangle, and a node as two (a triangulation has about twice
/// as many triangles as nodes), as in msh4_contents.
void check_counts(double nodes, double elements, const std::filesystem::path& file,
                  const MeshSource& source) {
  const std::string problem =
      mesh_budget_problem(std::max(2.0 * nodes, elements), available_memory_bytes());
  if (!problem.empty())
    source.fail(problem + ", counting " + count_text(elements) +
                " elements of any kind and 2 triangles a node for " + count_text(nodes) +
                " nodes (in " + file.string() + ")");
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

  // Sections first, by the prefixes Gmsh's format-2 reader matches: a second $Nodes section
  // made Gmsh 4.8 crash (SIGSEGV in GModel::_associateEntityWithMeshVertices, found by
  // fuzzing), and sections of format 1 ($NOD, $ELM) would pass by the checks below.
  const long body = std::ftell(fp.get());
  int node_sections = 0, element_sections = 0;
  while (std::fgets(line, sizeof line, fp.get())) {
    if (line[0] != '$') continue;
    node_sections += std::strncmp(line, "$Nodes", 6) == 0;
    element_sections += std::strncmp(line, "$Elements", 9) == 0;
    for (const char* old : {"$NOD", "$NOE", "$ELM", "$ParametricNodes"})
      if (std::strncmp(line, old, std::strlen(old)) == 0)
        source.fail("expected the $Nodes and $Elements sections of format 2.2, got a " +
                    std::string(old) + " section (in " + file.string() + ")");
  }
  if (node_sections > 1 || element_sections > 1)
    source.fail("expected one $Nodes and one $Elements section, got " +
                std::to_string(node_sections) + " and " + std::to_string(element_sections) +
                " (in " + file.string() + ")");
  if (body < 0 || std::fseek(fp.get(), body, SEEK_SET) != 0) return;

  // Past the header, whatever the reader cannot take as Gmsh would is refused rather than
  // left to Gmsh: a count Gmsh's sscanf fails on left its own count unset, and the elements
  // read after it reached an assertion in Gmsh 4.8 (found by fuzzing).
  auto unreadable = [&](const std::string& what) {
    source.fail("expected " + what + " (in " + file.string() + ")");
  };
  std::unordered_set<int> nodes;
  while (std::fgets(line, sizeof line, fp.get())) {
    if (std::strncmp(line, "$Nodes", 6) == 0) {
      int count = 0;
      if (std::fscanf(fp.get(), "%d", &count) != 1 || count < 0)
        unreadable("a node count after $Nodes");
      check_counts(count, 0, file, source);
      for (int n = 0; n < count; ++n) {
        int tag = 0;
        double x, y, z;
        if (std::fscanf(fp.get(), "%d %lf %lf %lf", &tag, &x, &y, &z) != 4)
          unreadable("node " + std::to_string(n + 1) + " of " + std::to_string(count) +
                     " as a tag and three coordinates");
        nodes.insert(tag);
      }
    } else if (std::strncmp(line, "$Elements", 9) == 0) {
      int count = 0;
      if (std::fscanf(fp.get(), "%d", &count) != 1 || count < 0)
        unreadable("an element count after $Elements");
      check_counts(static_cast<double>(nodes.size()), count, file, source);
      for (int e = 0; e < count; ++e) {
        int tag = 0, type = 0, tags = 0, value = 0;
        if (std::fscanf(fp.get(), "%d %d %d", &tag, &type, &tags) != 3 || tags < 0)
          unreadable("element " + std::to_string(e + 1) + " of " + std::to_string(count) +
                     " to start with its tag, type and number of tags");
        // Physical and entity tags, then (format 2.2) a partition count, the partitions and
        // further tags. Gmsh 4.8 crashes on partition lists and extra tags of format 2 (an
        // assertion, an invalid free, a segmentation fault: found by fuzzing), and rockdd
        // reads no partitioned mesh: at most a third tag, a partition count of 0.
        for (int t = 0; t < tags; ++t) {
          if (std::fscanf(fp.get(), "%d", &value) != 1)
            unreadable("the " + std::to_string(tags) + " tags of element " + std::to_string(tag));
          if (t == 3 || (t == 2 && value != 0))
            source.fail(
                "expected at most 3 tags per element (physical, elementary, and a "
                "partition count of 0: rockdd reads no partitioned mesh), got element " +
                std::to_string(tag) + " with " + std::to_string(tags) + " tags (in " +
                file.string() + ")");
        }
        const int corners = msh_nodes_of_type(type);
        if (corners == 0)
          unreadable("element types 1 to 31 of format 2, got type " + std::to_string(type) +
                     " for element " + std::to_string(tag));
        for (int c = 0; c < corners; ++c) {
          if (std::fscanf(fp.get(), "%d", &value) != 1)
            unreadable("the " + std::to_string(corners) + " nodes of element " +
                       std::to_string(tag));
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

#include "engine/mesh/msh4_contents.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "engine/mesh/msh_element_types.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "engine/scene/mesh_budget.hpp"

namespace rockdd {

namespace {

constexpr std::array<const char*, 4> kEntityNames = {"point", "curve", "surface", "volume"};

std::string text(std::int64_t value) {
  return std::to_string(value);
}

/// The entities of $Entities, sorted tags by dimension; `present` false when the file has no
/// $Entities section (Gmsh then makes the entities that the blocks name).
struct Entities {
  bool present = false;
  std::array<std::vector<std::int64_t>, 4> tags;
  bool has(std::int64_t dim, std::int64_t tag) const {
    return std::binary_search(tags[dim].begin(), tags[dim].end(), tag);
  }
};

/// Fails unless `count`, read just now, is >= 0 (an ASCII "-1" that Gmsh's %lu would wrap).
void require_count(MshReader& in, std::int64_t count, const std::string& what) {
  if (count < 0) in.fail("expected " + what + " >= 0, got " + text(count));
}

/// Skips the lines up to `end` (a section rockdd reads, but another check screens).
void skip_to(MshReader& in, std::string_view end) {
  while (const auto line = in.line())
    if (*line == end) return;
  in.fail("expected " + std::string(end) + ", got the end of the file");
}

void expect_line(MshReader& in, std::string_view expected, const std::string& after) {
  const auto line = in.line();
  if (!line)
    in.fail("expected " + std::string(expected) + " " + after + ", got the end of the file");
  if (*line != expected)
    in.fail("expected " + std::string(expected) + " " + after + ", got " + printable_text(*line));
}

/// The budget of a mesh file, checked from a section's header before its blocks are read: its
/// elements of every kind count as triangles, and so does half a node each (a triangulation
/// has about twice as many triangles as nodes), so neither a long $Nodes nor a long $Elements
/// reaches Gmsh beyond what a run could hold.
void check_budget(MshReader& in, std::int64_t nodes, std::int64_t elements) {
  const double triangles =
      std::max(2.0 * static_cast<double>(nodes), static_cast<double>(elements));
  const std::string problem = mesh_budget_problem(triangles, available_memory_bytes());
  if (problem.empty()) return;
  in.fail(problem + ", counting " + text(elements) +
          " elements of any kind and 2 triangles a node for " + text(nodes) + " nodes");
}

/// The tags a section's blocks give: each within the header's [min, max], each once.
struct TagRange {
  std::int64_t min = 0, max = 0;
  std::string header;  // where the header is ("line N"), for messages
};

/// Reads a section header "<blocks> <count> <min tag> <max tag>" of $Nodes or $Elements.
struct SectionHeader {
  std::int64_t blocks = 0, count = 0;
  TagRange tags;
};

SectionHeader read_header(MshReader& in, const char* section, const char* things) {
  SectionHeader header;
  const std::string of = std::string(" of the ") + section + " header";
  header.blocks = in.integer(MshField::size, "the number of entity blocks");
  require_count(in, header.blocks, "the number of entity blocks" + of);
  header.count = in.integer(MshField::size, "the number of entries");
  require_count(in, header.count, std::string("the number of ") + things + of);
  header.tags.min = in.integer(MshField::size, "the smallest tag");
  header.tags.max = in.integer(MshField::size, "the largest tag");
  header.tags.header = in.position();
  if (header.count > 0 && !(1 <= header.tags.min && header.tags.min <= header.tags.max))
    in.fail(std::string("expected the ") + section +
            " header <blocks> <count> <smallest tag> <largest tag> with 1 <= smallest <= "
            "largest, got smallest " +
            text(header.tags.min) + " and largest " + text(header.tags.max));
  return header;
}

/// Reads a block's "<dim> <tag>" and fails unless it names an entity of $Entities.
std::int64_t read_block_entity(MshReader& in, const Entities& entities, const char* section,
                               std::int64_t block) {
  const std::int64_t dim = in.integer(MshField::int32, "a block's entity dimension");
  if (dim < 0 || dim > 3)
    in.fail(std::string("expected block ") + text(block) + " of " + section +
            " on an entity of dimension 0 to 3, got dimension " + text(dim));
  const std::int64_t tag = in.integer(MshField::int32, "a block's entity tag");
  if (tag < 1 || (entities.present && !entities.has(dim, tag)))
    in.fail(std::string("expected block ") + text(block) + " of " + section + " on " +
            (entities.present ? "one of the " + text(entities.tags[dim].size()) + " " +
                                    kEntityNames[dim] + "s of $Entities"
                              : std::string("a ") + kEntityNames[dim] + " of tag >= 1") +
            ", got " + kEntityNames[dim] + " " + text(tag));
  return dim;
}

/// Fails unless the blocks read so far, `total`, plus `more` stay within the header's count.
void require_room(MshReader& in, const SectionHeader& header, std::int64_t total, std::int64_t more,
                  const char* section, const char* things, std::int64_t block) {
  if (more <= header.count - total) return;
  in.fail(std::string("expected the blocks of ") + section + " to hold the " + text(header.count) +
          " " + things + " its header declares (" + header.tags.header + "), got " +
          text(total + more) + " by block " + text(block));
}

void require_unique(MshReader& in, std::vector<std::int64_t>& tags, const std::string& what) {
  std::sort(tags.begin(), tags.end());
  const auto twice = std::adjacent_find(tags.begin(), tags.end());
  if (twice != tags.end())
    in.fail("expected each " + what + " once, got " + what + " " + text(*twice) + " twice");
}

Entities read_entities(MshReader& in) {
  Entities entities;
  entities.present = true;
  std::array<std::int64_t, 4> counts{};
  for (int dim = 0; dim < 4; ++dim) {
    counts[dim] = in.integer(MshField::size, "the number of entities of a dimension");
    require_count(in, counts[dim], std::string("the number of ") + kEntityNames[dim] + "s");
  }
  for (int dim = 0; dim < 4; ++dim) {
    const std::string name = kEntityNames[dim];
    for (std::int64_t i = 0; i < counts[dim]; ++i) {
      const std::int64_t tag = in.integer(MshField::int32, "an entity tag");
      if (tag < 1) in.fail("expected " + name + " tags >= 1, got " + text(tag));
      for (int x = 0; x < (dim == 0 ? 3 : 6); ++x) in.real("an entity's coordinates");
      const std::int64_t physicals = in.integer(MshField::size, "a number of physical tags");
      require_count(in, physicals, "the number of physical tags of " + name + " " + text(tag));
      for (std::int64_t p = 0; p < physicals; ++p) {
        const std::int64_t physical = in.integer(MshField::int32, "a physical tag");
        if (physical < 1)
          in.fail("expected physical tags >= 1, got " + text(physical) + " on " + name + " " +
                  text(tag));
      }
      if (dim > 0) {
        const std::int64_t bounds = in.integer(MshField::size, "a number of bounding entities");
        require_count(in, bounds, "the number of bounding entities of " + name + " " + text(tag));
        for (std::int64_t b = 0; b < bounds; ++b) {
          const std::int64_t bound = in.integer(MshField::int32, "a bounding entity tag");
          if (bound == 0 || !entities.has(dim - 1, bound < 0 ? -bound : bound))
            in.fail("expected the bounding " + std::string(kEntityNames[dim - 1]) + "s of " + name +
                    " " + text(tag) + " among the " + text(entities.tags[dim - 1].size()) + " " +
                    kEntityNames[dim - 1] +
                    "s of $Entities (a sign gives the "
                    "orientation), got " +
                    text(bound));
        }
      }
      entities.tags[dim].push_back(tag);
    }
    require_unique(in, entities.tags[dim], name + " tag");
  }
  return entities;
}

std::vector<std::int64_t> read_nodes(MshReader& in, const Entities& entities) {
  const SectionHeader header = read_header(in, "$Nodes", "nodes");
  check_budget(in, header.count, 0);
  std::vector<std::int64_t> tags;
  tags.reserve(static_cast<std::size_t>(std::min<std::int64_t>(header.count, 1 << 20)));
  std::int64_t total = 0;
  for (std::int64_t block = 1; block <= header.blocks; ++block) {
    const std::int64_t dim = read_block_entity(in, entities, "$Nodes", block);
    const std::int64_t parametric = in.integer(MshField::int32, "a block's parametric flag");
    if (parametric != 0 && parametric != 1)
      in.fail("expected the parametric flag of block " + text(block) + " of $Nodes, 0 or 1, got " +
              text(parametric));
    const std::int64_t count = in.integer(MshField::size, "a block's number of nodes");
    require_count(in, count, "the number of nodes of block " + text(block) + " of $Nodes");
    require_room(in, header, total, count, "$Nodes", "nodes", block);
    total += count;
    for (std::int64_t n = 0; n < count; ++n) {
      const std::int64_t tag = in.integer(MshField::size, "a node tag");
      if (tag < header.tags.min || tag > header.tags.max)
        in.fail("expected node tags in [" + text(header.tags.min) + ", " + text(header.tags.max) +
                "] (the $Nodes header, " + header.tags.header + "), got " + text(tag));
      tags.push_back(tag);
    }
    // x y z, then u (curves), u v (surfaces) or u v w (volumes) when parametric.
    const std::int64_t per_node = 3 + (parametric ? dim : 0);
    for (std::int64_t x = 0; x < count * per_node; ++x) in.real("a node's coordinates");
  }
  if (total != header.count)
    in.fail("expected the blocks of $Nodes to hold the " + text(header.count) +
            " nodes its header declares (" + header.tags.header + "), got " + text(total));
  require_unique(in, tags, "node tag");
  return tags;
}

void read_elements(MshReader& in, const Entities& entities,
                   const std::vector<std::int64_t>& nodes) {
  const SectionHeader header = read_header(in, "$Elements", "elements");
  check_budget(in, static_cast<std::int64_t>(nodes.size()), header.count);
  std::vector<std::int64_t> tags;
  tags.reserve(static_cast<std::size_t>(std::min<std::int64_t>(header.count, 1 << 20)));
  std::int64_t total = 0;
  for (std::int64_t block = 1; block <= header.blocks; ++block) {
    const std::int64_t dim = read_block_entity(in, entities, "$Elements", block);
    const std::int64_t type = in.integer(MshField::int32, "a block's element type");
    const int corners = msh_nodes_of_type(type);
    if (corners == 0)
      in.fail("expected element types 1 to 31 in block " + text(block) + " of $Elements, got " +
              text(type));
    if (msh_dimension_of_type(type) != dim)
      in.fail("expected elements of dimension " + text(dim) + " in block " + text(block) +
              " of $Elements (on a " + kEntityNames[dim] + "), got type " + text(type) +
              " of dimension " + text(msh_dimension_of_type(type)));
    const std::int64_t count = in.integer(MshField::size, "a block's number of elements");
    require_count(in, count, "the number of elements of block " + text(block) + " of $Elements");
    require_room(in, header, total, count, "$Elements", "elements", block);
    total += count;
    for (std::int64_t e = 0; e < count; ++e) {
      const std::int64_t tag = in.integer(MshField::size, "an element tag");
      if (tag < header.tags.min || tag > header.tags.max)
        in.fail("expected element tags in [" + text(header.tags.min) + ", " +
                text(header.tags.max) + "] (the $Elements header, " + header.tags.header +
                "), got " + text(tag));
      tags.push_back(tag);
      for (int c = 0; c < corners; ++c) {
        const std::int64_t node = in.integer(MshField::size, "an element's node tag");
        if (!std::binary_search(nodes.begin(), nodes.end(), node))
          in.fail("expected the nodes of element " + text(tag) + " among the " +
                  text(nodes.size()) + " nodes of $Nodes, got node " + text(node));
      }
    }
  }
  if (total != header.count)
    in.fail("expected the blocks of $Elements to hold the " + text(header.count) +
            " elements its header declares (" + header.tags.header + "), got " + text(total));
  require_unique(in, tags, "element tag");
}

}  // namespace

// Gmsh 4.8's format-4 reader trusts the file: a $Nodes header that declares fewer nodes than
// its blocks hold made it write past its node table (heap corruption, abort), and an element
// naming node -1 made it crash (SIGSEGV) when rockdd read the elements back (issue 28). The
// file is read here field by field as Gmsh reads it, and anything Gmsh would take on trust is
// checked first.
void check_msh4_contents(const std::filesystem::path& file, const MeshSource& source) {
  MshReader in(file, source);
  const auto first = in.line();
  const auto second = in.line();
  if (!first || *first != "$MeshFormat" || !second) return;  // check_msh_header refuses it
  std::istringstream fields{std::string(*second)};
  double version = 0.0;
  int file_type = -1;
  fields >> version >> file_type;
  if (version != 4.1) return;  // format 2 has its own check
  if (file_type == 1) {
    in.binary();
    const std::int64_t one = in.integer(MshField::int32, "the binary file's word 1");
    if (one != 1)
      in.fail(
          "expected the word 1 after the header of a binary .msh (the byte order of this "
          "machine), got " +
          text(one));
  }
  expect_line(in, "$EndMeshFormat", "after the format line");

  Entities entities;
  std::vector<std::int64_t> nodes;
  bool names = false, nodes_read = false, elements_read = false;
  while (const auto line = in.line()) {
    const std::string section(*line);
    if (section == "$PhysicalNames" && !names) {
      names = true;
      skip_to(in, "$EndPhysicalNames");  // check_msh_physical_names reads them
      continue;
    }
    if (section == "$Entities" && !entities.present && !nodes_read) {
      entities = read_entities(in);
    } else if (section == "$Nodes" && !nodes_read) {
      nodes = read_nodes(in, entities);
      nodes_read = true;
    } else if (section == "$Elements" && nodes_read && !elements_read) {
      read_elements(in, entities, nodes);
      elements_read = true;
    } else {
      in.fail(
          "expected the sections $PhysicalNames, $Entities, $Nodes and $Elements of format "
          "4.1, each once and in that order (rockdd reads no other), got " +
          printable_text(section) +
          (section == "$Elements" && !nodes_read ? " before $Nodes" : ""));
    }
    expect_line(in, "$End" + section.substr(1), "after the " + section + " section's entries");
  }
  if (!nodes_read || !elements_read)
    in.fail(std::string("expected a $Nodes and an $Elements section, got ") +
            (nodes_read ? "no $Elements" : "no $Nodes"));
}

}  // namespace rockdd

#include "engine/scene/scene_sections.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "engine/common/errors.hpp"
#include "engine/scene/geometry_limits.hpp"
#include "engine/scene/mesh_algorithm.hpp"
#include "engine/scene/mesh_budget.hpp"
#include "engine/scene/step_budget.hpp"

namespace rockdd {
namespace {

namespace fs = std::filesystem;

/// Stands in for a table the scene leaves out, so its defaults are recorded the same way.
const toml::table& empty_table() {
  static const toml::table empty;
  return empty;
}

/// The reader of the optional table `key`, or of an empty table with the same key path.
TableReader optional_table(TableReader& root, std::string_view key) {
  if (auto table = sub_table(root, key)) return *table;
  return TableReader(empty_table(), root.key_path(key), root.file(), root.defaults());
}

/// The scene name becomes the output folder `DIR/<name>/`: it must be one plain folder name.
void check_folder_name(const TableReader& table, const std::string& name) {
  const bool bad =
      name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos ||
      std::any_of(name.begin(), name.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; });
  if (bad) {
    table.fail("name",
               "expected a name usable as one folder name (no '/', not '.' or '..'), got \"" +
                   name + "\"");
  }
}

/// `geo` or `msh`: the file, resolved against the scene's folder, must exist and be readable.
fs::path readable_file(const TableReader& table, std::string_view key, const fs::path& scene_dir) {
  const std::string name = *table.string(key);
  fs::path file = (scene_dir / fs::path(name)).lexically_normal();
  std::error_code error;
  const auto status = fs::status(file, error);
  std::string problem;
  if (!fs::exists(status)) {
    problem = "does not exist";
  } else if (!fs::is_regular_file(status)) {
    problem = "is not a regular file";
  } else if (!std::ifstream(file)) {
    problem = "cannot be read";
  }
  if (!problem.empty()) {
    table.fail(key, "expected a readable file (relative to the scene's folder), got \"" + name +
                        "\": " + file.string() + " " + problem);
  }
  return file;
}

/// Refuses each key of `keys` that `table` has, saying which mesh source they do not apply to.
void refuse_keys(const TableReader& table, std::initializer_list<std::string_view> keys,
                 const std::string& source) {
  for (const std::string& key : table.present(keys)) {
    table.fail(key, "expected no " + table.key_path(key) + " with " + source +
                        ", got one (it belongs to another mesh source)");
  }
}

/// A length in m the kernels can compute with (geometry_limits): finite, in [1e-50, 1e50].
Range length_range() {
  return between(kShortestLength, true, kLongestLength, true);
}

/// [x, y], both lengths in length_range().
Vec2 length_pair(const TableReader& table, std::string_view key) {
  const std::string expected = "expected an array of 2 numbers " + length_range_text();
  const auto pair = table.vec2(key);
  if (!pair) table.fail(key, expected + ", got nothing (the key is required)");
  if (!length_in_range((*pair)[0]) || !length_in_range((*pair)[1]))
    table.fail(key, expected + ", got " + describe(*table.find(key)));
  return *pair;
}

/// [nx, ny], integers >= 1.
std::array<int, 2> divisions(const TableReader& table, std::string_view key) {
  const toml::node& node = *table.find(key);
  const auto* array = node.as_array();
  const auto count = [](const toml::node* n) {
    return n && n->is_integer() && n->as_integer()->get() >= 1 && n->as_integer()->get() <= INT_MAX;
  };
  if (!array || array->size() != 2 || !count(array->get(0)) || !count(array->get(1))) {
    table.fail(key, "expected an array of 2 integers >= 1 [nx, ny], got " + describe(node));
  }
  return {static_cast<int>(array->get(0)->as_integer()->get()),
          static_cast<int>(array->get(1)->as_integer()->get())};
}

Vec2 origin_or_default(TableReader& table) {
  if (auto origin = table.vec2("origin")) {
    if (!coordinate_in_range((*origin)[0]) || !coordinate_in_range((*origin)[1]))
      table.fail("origin", "expected an array of 2 numbers in [-" + format_number(kLongestLength) +
                               ", " + format_number(kLongestLength) + "] m, got " +
                               describe(*table.find("origin")));
    return *origin;
  }
  table.record_default("origin", "[0, 0]");
  return {0.0, 0.0};
}

void read_rectangle(TableReader& table, MeshSpec& mesh) {
  refuse_keys(table, {"radius", "flat_half_angle_deg"}, "shape = \"rectangle\"");
  mesh.kind = MeshSpec::Kind::rectangle;
  mesh.size = length_pair(table, "size");
  mesh.origin = origin_or_default(table);
  if (table.has("divisions") && mesh.element_size) {
    table.fail("divisions", "expected divisions or element_size for a rectangle, not both");
  }
  if (!table.has("divisions") && !mesh.element_size) {
    table.fail("divisions",
               "expected divisions = [nx, ny] or element_size for a rectangle, got neither");
  }
  if (table.has("divisions")) mesh.divisions = divisions(table, "divisions");
}

void read_disk(TableReader& table, MeshSpec& mesh) {
  refuse_keys(table, {"size", "divisions"}, "shape = \"disk\"");
  mesh.kind = MeshSpec::Kind::disk;
  mesh.radius = table.required_number("radius", length_range());
  mesh.flat_half_angle_deg =
      table.number_or("flat_half_angle_deg", 0.0, between(0, true, 90, false));
  mesh.origin = origin_or_default(table);
  if (!mesh.element_size) {
    table.fail("element_size",
               "expected a number > 0 for a disk, got nothing (the key is required)");
  }
}

/// mesh.algorithm and mesh.smoothing, for a mesh Gmsh draws unstructured. A built-in shape
/// gets the scene's defaults, recorded; a .geo without them keeps its own Mesh.Algorithm and
/// Mesh.Smoothing (Gmsh's defaults, the same as the scene's, unless it sets them): the file
/// chooses there, not the reader, so nothing is recorded.
void read_mesher_options(TableReader& table, MeshSpec& mesh) {
  const bool builtin = mesh.kind != MeshSpec::Kind::geo;
  if (const auto name =
          table.choice("algorithm", {"frontal-delaunay", "delaunay", "meshadapt", "automatic"})) {
    mesh.algorithm = scene_mesh_algorithm(*name);
  } else if (builtin) {
    mesh.algorithm = kDefaultMeshAlgorithm;
    table.record_default("algorithm", std::string(mesh_algorithm_name(kDefaultMeshAlgorithm)));
  }
  if (const auto passes = table.integer("smoothing", 0, kMaxMeshSmoothing)) {
    mesh.smoothing = static_cast<int>(*passes);
  } else if (builtin) {
    mesh.smoothing = kDefaultMeshSmoothing;
    table.record_default("smoothing", std::to_string(kDefaultMeshSmoothing));
  }
}

/// Refuses mesh.algorithm and mesh.smoothing where Gmsh does not triangulate: they would
/// silently do nothing. `what` says why ("a .msh is already meshed").
void refuse_mesher_options(const TableReader& table, const std::string& source,
                           const std::string& why) {
  for (const std::string& key : table.present({"algorithm", "smoothing"})) {
    std::string expected = "expected no " + table.key_path(key);
    expected.append(" with ").append(source).append(" (").append(why).append("), got one");
    table.fail(key, expected);
  }
}

/// The key that sets a built-in shape's element count: what a message about it must name.
std::string_view count_key(const MeshSpec& mesh) {
  return mesh.element_size ? "element_size" : "divisions";
}

/// Refuses, before any meshing, a built-in shape whose triangles would not fit in memory
/// (or exceed kMostTriangles), with the estimate and the memory available in the message.
void check_mesh_budget(const TableReader& table, const MeshSpec& mesh) {
  const std::optional<double> triangles = estimated_triangles(mesh);
  if (!triangles) return;
  const std::string problem = mesh_budget_problem(*triangles, available_memory_bytes());
  if (!problem.empty()) table.fail(count_key(mesh), problem);
}

/// Refuses a built-in shape so far from the origin, against its element size, that rounding
/// of the node positions swamps the strains (geometry_limits).
void check_precision(const TableReader& table, const MeshSpec& mesh) {
  const auto [x0, y0] = mesh.origin;
  double farthest = 0.0, element = 0.0;
  if (mesh.kind == MeshSpec::Kind::rectangle) {
    farthest = std::max(
        {std::abs(x0), std::abs(y0), std::abs(x0 + mesh.size[0]), std::abs(y0 + mesh.size[1])});
    element = mesh.element_size
                  ? std::min({*mesh.element_size, mesh.size[0], mesh.size[1]})
                  : std::min(mesh.size[0] / mesh.divisions[0], mesh.size[1] / mesh.divisions[1]);
  } else if (mesh.kind == MeshSpec::Kind::disk) {
    farthest = std::hypot(x0, y0) + mesh.radius;
    element = std::min(mesh.element_size.value_or(mesh.radius), mesh.radius);
  } else {
    return;
  }
  if (keeps_precision(farthest, element)) return;
  const std::string_view key = table.has("origin")                 ? "origin"
                               : mesh.kind == MeshSpec::Kind::disk ? "radius"
                                                                   : "size";
  table.fail(key, "expected " + precision_expectation() + ", got nodes " + format_number(farthest) +
                      " m from it with elements of " + format_number(element) + " m");
}

/// Refuses a run longer than time.max_steps (default kDefaultMaxSteps), naming the keys that
/// make its length and the one that raises the budget.
void check_step_budget(TableReader& table, TimeSpec& time) {
  if (auto most = table.integer("max_steps", 1, std::numeric_limits<std::int64_t>::max()))
    time.max_steps = *most;
  const double steps = scene_steps(time);
  if (steps <= static_cast<double>(time.max_steps)) return;
  const std::string budget = "at most time.max_steps = " + std::to_string(time.max_steps) +
                             (table.has("max_steps") ? "" : " (the default)") + " steps";
  if (time.steps)
    table.fail("steps", "expected " + budget + ", got " + std::to_string(*time.steps) +
                            ": raise time.max_steps to run more");
  table.fail("dt", "expected " + budget + ", got time.end / time.dt = " + format_number(*time.end) +
                       " / " + format_number(time.dt) + " = " + count_text(steps) +
                       " steps: lengthen time.dt, shorten time.end or raise time.max_steps");
}

}  // namespace

Scene read_scene_header(TableReader& root) {
  auto table = sub_table(root, "scene");
  if (!table)
    root.fail("scene", "expected a table [scene] with a name, got nothing (it is required)");
  table->allow_only({"name", "analysis", "plane", "thickness", "gravity"});
  Scene scene;
  scene.name = table->required_string("name");
  check_folder_name(*table, scene.name);
  const std::string analysis =
      table->choice_or("analysis", {"static", "quasi-static", "dynamic"}, "static");
  scene.analysis = analysis == "dynamic"        ? Analysis::dynamic
                   : analysis == "quasi-static" ? Analysis::quasi_static
                                                : Analysis::static_;
  scene.plane = table->choice_or("plane", {"stress", "strain"}, "stress") == "strain"
                    ? PlaneKind::strain
                    : PlaneKind::stress;
  scene.thickness = table->number_or("thickness", 1.0, length_range());
  if (auto gravity = table->vec2("gravity")) {
    scene.gravity = *gravity;
  } else {
    table->record_default("gravity", "[0, 0]");
  }
  return scene;
}

TimeSpec read_time(TableReader& root, Analysis analysis) {
  const bool is_static = analysis == Analysis::static_;
  if (!is_static && !root.has("time")) {
    // Point at the analysis line: that is what makes [time] required.
    const toml::node& analysis_node = *root.find("scene")->as_table()->get("analysis");
    throw InputError(where_of(analysis_node, root.file(), 0), "time",
                     "expected a table [time] (dt and end or steps) for analysis = \"" +
                         analysis_node.as_string()->get() + "\"" +
                         ", got nothing (only a \"static\" scene may leave it out)");
  }
  TableReader table = optional_table(root, "time");
  table.allow_only({"dt", "end", "steps", "max_steps", "dt_min", "max_step_displacement", "dt_max",
                    "integrator", "stop_at_softening", "softening_probe", "energy_tolerance"});
  TimeSpec time;
  time.dt =
      is_static ? table.number_or("dt", 1.0, above(0)) : table.required_number("dt", above(0));
  time.end = table.number("end", above(0));
  if (auto steps = table.integer("steps", 1, INT_MAX)) time.steps = static_cast<int>(*steps);
  if (time.end && time.steps) {
    table.fail("steps", "expected time.end or time.steps, not both; got end = " +
                            describe(*table.find("end")) +
                            " and steps = " + std::to_string(*time.steps));
  }
  if (!root.has("time")) {
    time.steps = 1;
    table.record_default("steps", "1");
  } else if (!time.end && !time.steps) {
    table.fail_table("expected time.end or time.steps, got neither");
  }
  const std::string dt = format_number(time.dt);
  time.dt_min = table.number_or("dt_min", time.dt * 1e-6, above(0));
  if (time.dt_min > time.dt) {
    table.fail("dt_min", "expected a number in (0, time.dt = " + dt + "], got " +
                             describe(*table.find("dt_min")));
  }
  check_step_budget(table, time);
  time.max_step_displacement = table.number("max_step_displacement", above(0));
  time.dt_max = table.number_or("dt_max", time.dt, above(0));
  if (time.dt_max < time.dt) {
    table.fail("dt_max",
               "expected a number >= time.dt = " + dt + ", got " + describe(*table.find("dt_max")));
  }
  time.energy_tolerance =
      table.number_or("energy_tolerance", kDefaultEnergyTolerance, between(0.0, false, 1.0, true));
  time.integrator = table.choice_or("integrator", {"dda", "newmark"}, "dda") == "newmark"
                        ? Integrator::newmark
                        : Integrator::dda;
  time.stop_at_softening = table.number("stop_at_softening", between(0.0, false, 1.0, false));
  if (auto probe = table.string("softening_probe")) time.softening_probe = *probe;
  if (time.stop_at_softening && time.softening_probe.empty())
    table.fail("stop_at_softening",
               "expected time.softening_probe (a history column \"<probe>.<field>\") with it");
  if (!time.stop_at_softening && !time.softening_probe.empty())
    table.fail("softening_probe", "expected time.stop_at_softening (a fraction in (0, 1)) with it");
  return time;
}

MeshSpec read_mesh(TableReader& root, const fs::path& scene_dir) {
  auto table = sub_table(root, "mesh");
  if (!table) {
    root.fail("mesh",
              "expected a table [mesh] with geo, msh or shape, got nothing (it is required)");
  }
  table->allow_only({"geo", "msh", "shape", "element_size", "size", "origin", "divisions", "radius",
                     "flat_half_angle_deg", "algorithm", "smoothing"});
  const auto sources = table->present({"geo", "msh", "shape"});
  if (sources.empty())
    table->fail_table("expected one of mesh.geo, mesh.msh, mesh.shape, got none");
  if (sources.size() > 1) {
    table->fail(sources[1], "expected exactly one of mesh.geo, mesh.msh, mesh.shape, got " +
                                sources[0] + " and " + sources[1]);
  }
  MeshSpec mesh;
  mesh.element_size = table->number("element_size", length_range());
  if (sources[0] == "geo" || sources[0] == "msh") {
    const std::string source = "mesh." + sources[0];
    refuse_keys(*table, {"size", "origin", "divisions", "radius", "flat_half_angle_deg"}, source);
    // A .msh is already meshed: a size cap would silently do nothing.
    if (sources[0] == "msh") refuse_keys(*table, {"element_size"}, source);
    mesh.kind = sources[0] == "geo" ? MeshSpec::Kind::geo : MeshSpec::Kind::msh;
    mesh.file = readable_file(*table, sources[0], scene_dir);
  } else if (*table->choice("shape", {"rectangle", "disk"}) == "rectangle") {
    read_rectangle(*table, mesh);
  } else {
    read_disk(*table, mesh);
  }
  if (mesh.kind == MeshSpec::Kind::msh)
    refuse_mesher_options(*table, "mesh.msh", "a .msh is already meshed");
  else if (mesh.kind == MeshSpec::Kind::rectangle && !mesh.element_size)
    refuse_mesher_options(*table, "mesh.divisions",
                          "a structured mesh; they apply to a rectangle with element_size");
  else
    read_mesher_options(*table, mesh);
  check_mesh_budget(*table, mesh);
  check_precision(*table, mesh);
  return mesh;
}

void check_softening_probe(TableReader& root, const Scene& scene) {
  if (!scene.time.stop_at_softening) return;
  const std::string& column = scene.time.softening_probe;
  for (const ProbeSpec& probe : scene.probes)
    for (const std::string& field : probe.fields)
      if (column == probe.name + "." + field) return;
  std::string columns;
  for (const ProbeSpec& probe : scene.probes)
    for (const std::string& field : probe.fields)
      if (probe.kind != ProbeSpec::Kind::line)
        columns += (columns.empty() ? "" : ", ") + probe.name + "." + field;
  optional_table(root, "time")
      .fail("softening_probe", "expected a history column (" +
                                   (columns.empty() ? std::string("the scene has none") : columns) +
                                   "), got \"" + column + "\"");
}

FractureSpec read_fracture(TableReader& root, bool has_damage, Analysis analysis) {
  // Defaults are listed only where they are used: in scenes whose materials can damage.
  if (!has_damage && !root.has("fracture")) return {};
  TableReader table = optional_table(root, "fracture");
  table.allow_only({"damage_band", "max_damage_passes", "fragment_stiffness", "loose_part_support",
                    "restraint_relaxation", "snap_back", "snap_back_dt", "locate_onsets",
                    "growth_tolerance"});
  FractureSpec fracture;
  fracture.damage_band = table.number_or("damage_band", fracture.damage_band, above(0));
  if (auto passes = table.integer("max_damage_passes", 1, 1000000)) {
    fracture.max_damage_passes = static_cast<int>(*passes);
  } else {
    table.record_default("max_damage_passes", std::to_string(fracture.max_damage_passes));
  }
  fracture.fragment_stiffness = table.number_or("fragment_stiffness", fracture.fragment_stiffness,
                                                between(0, false, 1, true));
  fracture.loose_part_support = table.number_or("loose_part_support", fracture.loose_part_support,
                                                between(0, false, 1e6, true));
  fracture.restraint_relaxation = table.number_or(
      "restraint_relaxation", fracture.restraint_relaxation, between(0, true, 1, true));
  if (table.choice_or("snap_back", {"held", "dynamic"}, "held") == "dynamic") {
    // A static analysis has no time to follow motion in; a dynamic one has inertia already.
    if (analysis != Analysis::quasi_static)
      table.fail("snap_back", std::string("expected \"held\" in a ") +
                                  (analysis == Analysis::static_ ? "static" : "dynamic") +
                                  " analysis (\"dynamic\" follows the damage cascades of a "
                                  "quasi-static one with inertia), got \"dynamic\"");
    fracture.snap_back = FractureSpec::SnapBack::dynamic;
  }
  if (table.has("snap_back_dt") && fracture.snap_back != FractureSpec::SnapBack::dynamic)
    table.fail("snap_back_dt", "expected no snap_back_dt unless snap_back = \"dynamic\"");
  fracture.snap_back_dt = table.number("snap_back_dt", above(0));
  if (const auto locate = table.boolean("locate_onsets"))
    fracture.locate_onsets = *locate;
  else
    table.record_default("locate_onsets", fracture.locate_onsets ? "true" : "false");
  fracture.growth_tolerance =
      table.number_or("growth_tolerance", fracture.growth_tolerance, between(0, true, 1, true));
  return fracture;
}

SolverSpec read_solver(TableReader& root) {
  SolverSpec solver;
  if (!root.has("solver")) return solver;
  TableReader table = optional_table(root, "solver");
  table.allow_only({"factor_updates"});
  solver.factor_updates = table.boolean("factor_updates").value_or(solver.factor_updates);
  return solver;
}

OutputSpec read_output(TableReader& root) {
  TableReader table = optional_table(root, "output");
  table.allow_only({"dir", "every", "fields", "compress"});
  OutputSpec output;
  if (auto dir = table.string("dir")) {
    output.dir = *dir;
  } else {
    table.record_default("dir", output.dir.string());
  }
  if (auto every = table.integer("every", 0, INT_MAX)) {
    output.every = static_cast<int>(*every);
  } else {
    table.record_default("every", std::to_string(output.every));
  }
  if (auto fields = table.strings("fields", {"displacement", "velocity", "stress", "principal",
                                             "damage", "block", "material", "strain"})) {
    output.fields = *fields;
  } else {
    table.record_default(
        "fields",
        R"(["displacement", "velocity", "stress", "principal", "damage", "block", "material"])");
  }
  // Not recorded in defaults when left out, like time.max_steps: the scene contract's example
  // writes every key that has a default, and this one came later.
  output.compress = table.boolean("compress").value_or(output.compress);
  return output;
}

}  // namespace rockdd

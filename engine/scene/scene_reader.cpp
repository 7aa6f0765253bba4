#include "engine/scene/scene_reader.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "engine/common/errors.hpp"
#include "engine/scene/scene_entries.hpp"
#include "engine/scene/scene_overrides.hpp"
#include "engine/scene/scene_sections.hpp"
#include "engine/scene/table_reader.hpp"

namespace rockdd {
namespace {

namespace fs = std::filesystem;

/// The TOML document, or an InputError at toml++'s error position.
toml::table parse_toml(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& error) {
    const auto& begin = error.source().begin;
    throw InputError(file + ":" + std::to_string(begin.line), "",
                     "expected valid TOML, got: " + std::string(error.description()) + " (column " +
                         std::to_string(begin.column) + ")");
  }
}

}  // namespace

Scene parse_scene(std::string_view text, const fs::path& file,
                  const std::vector<std::string>& overrides) {
  const std::string name = file.string();
  toml::table document = parse_toml(text, name);
  apply_overrides(document, overrides, name);

  DefaultsLog defaults;
  TableReader root(document, "", name, defaults);
  root.allow_only({"scene", "time", "mesh", "material", "initial", "joint", "boundary", "load",
                   "probe", "fracture", "solver", "output"});
  Scene scene = read_scene_header(root);
  scene.file = fs::absolute(file).lexically_normal();
  scene.has_time = root.has("time");
  scene.time = read_time(root, scene.analysis);
  scene.mesh = read_mesh(root, scene.file.parent_path());
  scene.materials = read_materials(root, scene.plane);
  scene.initial = read_initial(root);
  scene.joints = read_joints(root);
  scene.boundaries = read_boundaries(root);
  scene.loads = read_loads(root);
  scene.probes = read_probes(root);
  check_softening_probe(root, scene);
  scene.fracture = read_fracture(root,
                                 std::any_of(scene.materials.begin(), scene.materials.end(),
                                             [](const MaterialSpec& m) { return m.has_damage(); }),
                                 scene.analysis);
  scene.solver = read_solver(root);
  scene.output = read_output(root);
  scene.defaults = std::move(defaults);
  return scene;
}

Scene read_scene(const fs::path& file, const std::vector<std::string>& overrides) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    throw InputError(
        file.string(), "",
        std::string("expected a scene file, got ") +
            (fs::exists(file, error) ? "something that is not a regular file" : "no such file"));
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(file.string(), "", "expected a readable scene file, got a read error");
  return parse_scene(text.str(), file, overrides);
}

}  // namespace rockdd

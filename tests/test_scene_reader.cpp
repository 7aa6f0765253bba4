// Scene reader: the scene contract's example (tests/scenes/good/full.toml) read field by field,
// defaults, --set overrides, and every malformed scene of tests/scenes/bad/ (listed in its
// CASES.md) rejected with the right key path, message and file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/common/errors.hpp"
#include "engine/scene/scene_reader.hpp"

namespace rockdd {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(ROCKDD_SOURCE_DIR) / "tests" / "scenes";

/// Runs `read`, which must throw InputError; returns the error for further checks.
InputError input_error(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError thrown";
  return InputError("", "", "");
}

std::map<std::string, std::string> as_map(const Scene& scene) {
  return {scene.defaults.begin(), scene.defaults.end()};
}

std::string text_of(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Numbers below are decimal literals read back by the TOML parser: compared exactly
// (EXPECT_DOUBLE_EQ, 4 ulp), since both sides are the nearest double to the same literal.
TEST(SceneReader, ReadsEveryFieldOfTheExample) {
  const fs::path file = kScenes / "good" / "full.toml";
  const Scene s = read_scene(file);
  EXPECT_EQ(s.file, fs::absolute(file).lexically_normal());
  EXPECT_EQ(s.name, "sliding-block");
  EXPECT_EQ(s.analysis, Analysis::dynamic);
  EXPECT_EQ(s.plane, PlaneKind::stress);
  EXPECT_DOUBLE_EQ(s.thickness, 1.0);
  EXPECT_DOUBLE_EQ(s.gravity[0], 0.0);
  EXPECT_DOUBLE_EQ(s.gravity[1], -10.0);

  EXPECT_TRUE(s.has_time);
  EXPECT_DOUBLE_EQ(s.time.dt, 1e-3);
  ASSERT_TRUE(s.time.end.has_value());
  EXPECT_DOUBLE_EQ(*s.time.end, 1.5);
  EXPECT_FALSE(s.time.steps.has_value());
  EXPECT_DOUBLE_EQ(s.time.dt_min, 1e-7);
  ASSERT_TRUE(s.time.max_step_displacement.has_value());
  EXPECT_DOUBLE_EQ(*s.time.max_step_displacement, 1e-3);
  EXPECT_DOUBLE_EQ(s.time.dt_max, 1e-3);
  EXPECT_DOUBLE_EQ(s.time.energy_tolerance, 2e-3);
  EXPECT_EQ(s.time.integrator, Integrator::dda);

  EXPECT_EQ(s.mesh.kind, MeshSpec::Kind::geo);
  EXPECT_EQ(s.mesh.file, (kScenes / "good" / "sliding_block.geo").lexically_normal());
  EXPECT_TRUE(s.mesh.file.is_absolute());
  ASSERT_TRUE(s.mesh.element_size.has_value());
  EXPECT_DOUBLE_EQ(*s.mesh.element_size, 0.05);

  ASSERT_EQ(s.materials.size(), 1u);
  const MaterialSpec& m = s.materials[0];
  EXPECT_EQ(m.body, "rock");
  EXPECT_DOUBLE_EQ(m.density, 2600.0);
  EXPECT_DOUBLE_EQ(m.young, 10e9);
  EXPECT_DOUBLE_EQ(m.poisson, 0.3);
  ASSERT_TRUE(m.tensile_strength && m.cohesion && m.friction_angle && m.homogeneity);
  EXPECT_DOUBLE_EQ(*m.tensile_strength, 2e6);
  EXPECT_DOUBLE_EQ(*m.cohesion, 100e6);
  EXPECT_FALSE(m.compressive_strength.has_value());
  EXPECT_DOUBLE_EQ(*m.friction_angle, 20.0);
  EXPECT_DOUBLE_EQ(m.residual, 0.1);
  EXPECT_DOUBLE_EQ(m.ultimate_strain, 5.0);
  EXPECT_EQ(m.tension_onset, TensionOnset::stress);
  EXPECT_DOUBLE_EQ(m.detach_at_damage, 0.0);
  EXPECT_DOUBLE_EQ(*m.homogeneity, 1.5);
  EXPECT_EQ(m.heterogeneous, (std::vector<std::string>{"young", "tensile_strength", "cohesion"}));
  EXPECT_EQ(m.seed, 42u);
  EXPECT_FALSE(m.weibull_size_scaling);
  EXPECT_TRUE(m.has_damage());

  ASSERT_EQ(s.initial.size(), 1u);
  EXPECT_EQ(s.initial[0].body, "block2");
  EXPECT_DOUBLE_EQ(s.initial[0].velocity[0], 1.0);
  EXPECT_DOUBLE_EQ(s.initial[0].velocity[1], 0.0);
  EXPECT_DOUBLE_EQ(s.initial[0].angular_velocity, 0.0);

  ASSERT_EQ(s.joints.size(), 1u);
  EXPECT_EQ(s.joints[0].between, (std::vector<std::string>{"block1", "block2"}));
  EXPECT_DOUBLE_EQ(s.joints[0].friction_angle, 0.0);
  EXPECT_DOUBLE_EQ(s.joints[0].cohesion, 0.0);
  EXPECT_DOUBLE_EQ(s.joints[0].tensile_strength, 0.0);
  ASSERT_TRUE(s.joints[0].normal_stiffness.has_value());
  EXPECT_DOUBLE_EQ(*s.joints[0].normal_stiffness, 1e11);
  EXPECT_FALSE(s.joints[0].shear_stiffness.has_value());

  ASSERT_EQ(s.boundaries.size(), 2u);
  EXPECT_EQ(s.boundaries[0].on, "left");
  EXPECT_TRUE(s.boundaries[0].fix_x && s.boundaries[0].fix_y);
  EXPECT_FALSE(s.boundaries[0].velocity_x || s.boundaries[0].velocity_y);
  EXPECT_EQ(s.boundaries[1].on, "top");
  EXPECT_FALSE(s.boundaries[1].fix_x || s.boundaries[1].fix_y);
  ASSERT_TRUE(s.boundaries[1].velocity_x && s.boundaries[1].velocity_y);
  EXPECT_DOUBLE_EQ(*s.boundaries[1].velocity_x, 0.0);
  EXPECT_DOUBLE_EQ(*s.boundaries[1].velocity_y, -2e-5);

  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].on, "tip");
  ASSERT_TRUE(s.loads[0].force.has_value());
  EXPECT_DOUBLE_EQ((*s.loads[0].force)[0], 0.0);
  EXPECT_DOUBLE_EQ((*s.loads[0].force)[1], -1e4);
  EXPECT_FALSE(s.loads[0].pressure || s.loads[0].force_density);

  ASSERT_EQ(s.probes.size(), 4u);
  EXPECT_EQ(s.probes[0].name, "tip");
  EXPECT_EQ(s.probes[0].kind, ProbeSpec::Kind::point);
  EXPECT_DOUBLE_EQ(s.probes[0].at[0], 0.04);
  EXPECT_DOUBLE_EQ(s.probes[0].at[1], 0.005);
  EXPECT_EQ(s.probes[0].fields, (std::vector<std::string>{"ux", "uy"}));
  EXPECT_EQ(s.probes[1].name, "platen");
  EXPECT_EQ(s.probes[1].kind, ProbeSpec::Kind::curve);
  EXPECT_EQ(s.probes[1].on, "top");
  EXPECT_EQ(s.probes[1].fields, (std::vector<std::string>{"fx", "fy", "ux", "uy"}));
  EXPECT_EQ(s.probes[2].kind, ProbeSpec::Kind::body);
  EXPECT_EQ(s.probes[2].body, "block2");
  EXPECT_EQ(s.probes[2].fields,
            (std::vector<std::string>{"ux", "uy", "vx", "vy", "rotation", "area", "kinetic"}));
  EXPECT_EQ(s.probes[3].name, "diameter");
  EXPECT_EQ(s.probes[3].kind, ProbeSpec::Kind::line);
  EXPECT_DOUBLE_EQ(s.probes[3].line[0][0], 0.0);
  EXPECT_DOUBLE_EQ(s.probes[3].line[0][1], -0.025);
  EXPECT_DOUBLE_EQ(s.probes[3].line[1][0], 0.0);
  EXPECT_DOUBLE_EQ(s.probes[3].line[1][1], 0.025);
  EXPECT_EQ(s.probes[3].samples, 101);
  EXPECT_EQ(s.probes[3].fields, (std::vector<std::string>{"sxx", "syy", "sxy"}));

  EXPECT_EQ(s.output.dir, fs::path("out"));
  EXPECT_EQ(s.output.every, 100);
  EXPECT_EQ(s.output.fields,
            (std::vector<std::string>{"displacement", "stress", "damage", "block"}));

  EXPECT_DOUBLE_EQ(s.fracture.damage_band, 1e-6);
  EXPECT_EQ(s.fracture.max_damage_passes, 500);
  EXPECT_TRUE(s.fracture.locate_onsets);
  EXPECT_DOUBLE_EQ(s.fracture.growth_tolerance, 3e-4);
  EXPECT_DOUBLE_EQ(s.fracture.fragment_stiffness, 1e-6);
  EXPECT_DOUBLE_EQ(s.fracture.loose_part_support, 1.0);
  EXPECT_DOUBLE_EQ(s.fracture.restraint_relaxation, 1e-3);
  EXPECT_EQ(s.fracture.snap_back, FractureSpec::SnapBack::held);
  EXPECT_FALSE(s.fracture.snap_back_dt.has_value());

  // The example writes every key that has a default: nothing was chosen for it.
  EXPECT_TRUE(s.defaults.empty()) << s.defaults.front().first;
}

TEST(SceneReader, StaticSceneWithoutTimeRunsOneStepAndRecordsEveryDefault) {
  const Scene s = read_scene(kScenes / "good" / "minimal_static.toml");
  EXPECT_EQ(s.analysis, Analysis::static_);
  EXPECT_FALSE(s.has_time);
  ASSERT_TRUE(s.time.steps.has_value());
  EXPECT_EQ(*s.time.steps, 1);
  EXPECT_FALSE(s.time.end.has_value());
  EXPECT_DOUBLE_EQ(s.time.dt, 1.0);
  EXPECT_DOUBLE_EQ(s.time.dt_min, 1e-6);             // dt * 1e-6
  EXPECT_DOUBLE_EQ(s.time.dt_max, 1.0);              // dt
  EXPECT_DOUBLE_EQ(s.materials[0].density, 2600.0);  // an integer where a float is expected
  EXPECT_EQ(s.mesh.kind, MeshSpec::Kind::rectangle);
  EXPECT_EQ(s.mesh.divisions, (std::array<int, 2>{8, 2}));
  const std::map<std::string, std::string> expected{
      {"scene.analysis", "static"},
      {"scene.plane", "stress"},
      {"scene.thickness", "1"},
      {"scene.gravity", "[0, 0]"},
      {"time.dt", "1"},
      {"time.steps", "1"},
      {"time.dt_min", "1e-06"},
      {"time.dt_max", "1"},
      {"time.energy_tolerance", "0.001"},
      {"time.integrator", "dda"},
      {"mesh.origin", "[0, 0]"},
      {"material[0].body", "*"},
      {"material[0].residual", "0.1"},
      {"material[0].ultimate_strain", "5"},
      {"material[0].tension_onset", "stress"},
      {"material[0].detach_at_damage", "1"},
      {"fracture.damage_band", "1e-06"},  // recorded since the material can damage
      {"fracture.max_damage_passes", "500"},
      {"fracture.locate_onsets", "true"},
      {"fracture.growth_tolerance", "3e-04"},
      {"fracture.fragment_stiffness", "1e-06"},
      {"fracture.loose_part_support", "1"},
      {"fracture.restraint_relaxation", "0.001"},
      {"fracture.snap_back", "held"},
      {"output.dir", "out"},
      {"output.every", "100"},
      {"output.fields",
       R"(["displacement", "velocity", "stress", "principal", "damage", "block", "material"])"},
  };
  EXPECT_EQ(as_map(s), expected);
  EXPECT_EQ(s.defaults.size(), expected.size()) << "a default recorded twice";
}

TEST(SceneReader, DamageDefaultsOnlyForMaterialsThatDamage) {
  const std::string text = R"(
[scene]
name = "two"
[mesh]
shape = "disk"
radius = 0.025
element_size = 5e-4
[[material]]
body = "elastic"
density = 2600.0
young = 10e9
poisson = 0.3
residual = 0.2
[[material]]
body = "rock"
density = 2600.0
young = 20e9
poisson = 0.5
cohesion = 1e6
friction_angle = 30
ultimate_strain = 3
)";
  const Scene s = parse_scene(text, kScenes / "good" / "virtual.toml");
  const auto d = as_map(s);
  EXPECT_EQ(d.count("material[0].residual"), 0u);
  EXPECT_EQ(d.count("material[0].ultimate_strain"), 0u);
  EXPECT_EQ(d.count("material[0].tension_onset"), 0u);
  EXPECT_DOUBLE_EQ(s.materials[0].residual, 0.2);  // validated and kept, though unused
  EXPECT_EQ(d.at("material[1].residual"), "0.1");
  EXPECT_EQ(d.count("material[1].ultimate_strain"), 0u);
  EXPECT_DOUBLE_EQ(s.materials[1].ultimate_strain, 3.0);
  EXPECT_DOUBLE_EQ(s.materials[1].poisson, 0.5);  // allowed in plane stress
  EXPECT_EQ(s.mesh.kind, MeshSpec::Kind::disk);
  EXPECT_DOUBLE_EQ(s.mesh.radius, 0.025);
  EXPECT_EQ(d.at("mesh.flat_half_angle_deg"), "0");
  EXPECT_EQ(d.at("mesh.origin"), "[0, 0]");
  // An unstructured built-in shape: Gmsh's algorithm and smoothing are the reader's defaults.
  EXPECT_EQ(d.at("mesh.algorithm"), "frontal-delaunay");
  EXPECT_EQ(d.at("mesh.smoothing"), "1");
  EXPECT_EQ(s.mesh.algorithm, MeshAlgorithm::frontal_delaunay);
  EXPECT_EQ(s.mesh.smoothing, 1);
}

TEST(SceneReader, MeshAlgorithmAndSmoothingReachTheMeshSpec) {
  const auto mesh_of = [](const std::string& mesh_table) {
    const std::string text = "[scene]\nname = \"m\"\nanalysis = \"static\"\n[mesh]\n" + mesh_table +
                             "\n[[material]]\ndensity = 1\nyoung = 1\npoisson = 0\n";
    return parse_scene(text, kScenes / "good" / "virtual.toml");
  };
  const Scene set = mesh_of(
      "shape = \"rectangle\"\nsize = [1, 1]\nelement_size = 0.1\nalgorithm = \"delaunay\"\n"
      "smoothing = 0");
  EXPECT_EQ(set.mesh.algorithm, MeshAlgorithm::delaunay);
  EXPECT_EQ(set.mesh.smoothing, 0);
  EXPECT_EQ(as_map(set).count("mesh.algorithm"), 0u);
  // A .geo keeps its own Mesh.Algorithm and Mesh.Smoothing unless the scene sets them: the
  // file chooses, so no default is recorded.
  const Scene geo = mesh_of("geo = \"sliding_block.geo\"");
  EXPECT_FALSE(geo.mesh.algorithm.has_value());
  EXPECT_FALSE(geo.mesh.smoothing.has_value());
  EXPECT_EQ(as_map(geo).count("mesh.algorithm"), 0u);
  EXPECT_EQ(as_map(geo).count("mesh.smoothing"), 0u);
  const Scene geo_set = mesh_of("geo = \"sliding_block.geo\"\nalgorithm = \"meshadapt\"");
  EXPECT_EQ(geo_set.mesh.algorithm, MeshAlgorithm::meshadapt);
  // Divisions make a structured mesh: nothing recorded, nothing set.
  const Scene grid = mesh_of("shape = \"rectangle\"\nsize = [1, 1]\ndivisions = [2, 2]");
  EXPECT_FALSE(grid.mesh.algorithm.has_value());
  EXPECT_EQ(as_map(grid).count("mesh.smoothing"), 0u);
}

TEST(SceneReader, ReadsEveryKindOfEntry) {
  const std::string text = R"(
[scene]
name = "kinds"
analysis = "quasi-static"
plane = "strain"
[time]
dt = 2e-4
steps = 50
integrator = "newmark"
[mesh]
msh = "../good/sliding_block.geo"  # the reader only checks that the file is readable
[[material]]
density = 2700.0
young = 50e9
poisson = 0.2
compressive_strength = 80e6
friction_angle = 20.0
tension_onset = "strain"
homogeneity = 1.5
heterogeneous = ["compressive_strength"]
[[joint]]
between = "*"
[[joint]]
between = ["b", "a"]
[[boundary]]
on = "bottom"
velocity_y = 0.0
[[boundary]]
on = "bottom"
fix = ["x"]
[[load]]
body = "rock"
force_density = [0.0, -2.7e4]
[[load]]
on = "bore"
pressure = 1e6
[[probe]]
name = "mid-line"
line = [[0, 0], [0.075, 0]]
fields = ["s1", "damage", "ux"]
[output]
every = 0
fields = []
)";
  const Scene s = parse_scene(text, kScenes / "good" / "kinds.toml");
  EXPECT_EQ(s.analysis, Analysis::quasi_static);
  EXPECT_EQ(s.plane, PlaneKind::strain);
  EXPECT_EQ(s.time.integrator, Integrator::newmark);
  EXPECT_EQ(*s.time.steps, 50);
  EXPECT_DOUBLE_EQ(s.time.dt_min, 2e-4 * 1e-6);
  EXPECT_EQ(s.mesh.kind, MeshSpec::Kind::msh);
  EXPECT_EQ(s.materials[0].tension_onset, TensionOnset::strain);
  EXPECT_EQ(as_map(s).at("material[0].seed"), "0");
  EXPECT_EQ(s.joints[0].between, (std::vector<std::string>{"*"}));
  EXPECT_EQ(as_map(s).at("joint[1].friction_angle"), "0");
  EXPECT_TRUE(s.boundaries[1].fix_x);
  EXPECT_EQ(*s.boundaries[0].velocity_y, 0.0);
  EXPECT_EQ(s.loads[0].body, "rock");
  EXPECT_DOUBLE_EQ((*s.loads[0].force_density)[1], -2.7e4);
  EXPECT_DOUBLE_EQ(*s.loads[1].pressure, 1e6);
  EXPECT_EQ(s.probes[0].samples, 101);
  EXPECT_EQ(as_map(s).at("probe[0].samples"), "101");
  EXPECT_EQ(s.output.every, 0);
  EXPECT_TRUE(s.output.fields.empty());
}

TEST(SceneReader, OverridesReplaceValuesIncludingArrayOfTablesEntries) {
  const Scene s =
      read_scene(kScenes / "good" / "full.toml",
                 {"time.dt=1e-4", "mesh.element_size=5e-4", "scene.analysis=quasi-static",
                  "material.0.young=2e10", "boundary.1.velocity=[0,-1e-5]", "probe.3.samples = 11",
                  "scene.plane=\"strain\""});
  EXPECT_DOUBLE_EQ(s.time.dt, 1e-4);
  EXPECT_DOUBLE_EQ(*s.mesh.element_size, 5e-4);
  EXPECT_EQ(s.analysis, Analysis::quasi_static);  // a bare word is taken as a string
  EXPECT_EQ(s.plane, PlaneKind::strain);          // so is a quoted TOML string
  EXPECT_DOUBLE_EQ(s.materials[0].young, 2e10);
  EXPECT_DOUBLE_EQ(*s.boundaries[1].velocity_x, 0.0);
  EXPECT_DOUBLE_EQ(*s.boundaries[1].velocity_y, -1e-5);
  EXPECT_EQ(s.probes[3].samples, 11);
  EXPECT_DOUBLE_EQ(s.materials[0].density, 2600.0);  // untouched keys keep their values
}

TEST(SceneReader, OverridesMayCreateKeysAndTables) {
  const Scene s =
      read_scene(kScenes / "good" / "minimal_static.toml",
                 {"time.steps=4", "output.every=0", "material.0.seed=7", "scene.thickness=.5"});
  EXPECT_TRUE(s.has_time);
  EXPECT_EQ(*s.time.steps, 4);
  EXPECT_DOUBLE_EQ(s.time.dt, 1.0);  // static: dt defaults to 1
  EXPECT_EQ(as_map(s).at("time.dt"), "1");
  EXPECT_EQ(as_map(s).count("time.steps"), 0u);
  EXPECT_EQ(s.output.every, 0);
  EXPECT_EQ(s.materials[0].seed, 7u);
  EXPECT_DOUBLE_EQ(s.thickness, 0.5);  // not TOML, but a number: read as one
}

TEST(SceneReader, BadOverridesNameTheOverride) {
  const fs::path file = kScenes / "good" / "full.toml";
  const std::string name = file.string();
  struct Bad {
    std::string set, key, phrase;
  };
  const std::vector<Bad> cases{
      {"time.dt=0", "time.dt", "expected a number > 0, got 0"},
      {"output={every=-3}", "output.every", "expected an integer >= 0, got -3"},
      {"scene.analysis=explicit", "scene.analysis", "got the string \"explicit\""},
      {"material.0.yung=1", "material[0].yung", "did you mean \"young\"?"},
      {"material.1.young=1", "material[1]", "expected an index below 1"},
      {"boundary.x.on=\"top\"", "boundary[x]", "expected an index below 2"},
      {"time.dt.x=1", "time.dt", "expected a table to set a key inside, got 0.001"},
      {"time.dt", "", "expected --set key.path=value"},
      {"time..dt=1", "time..dt", "expected a key path of names joined by '.'"},
  };
  for (const Bad& bad : cases) {
    SCOPED_TRACE(bad.set);
    const InputError e = input_error([&] { read_scene(file, {bad.set}); });
    EXPECT_EQ(e.key(), bad.key);
    EXPECT_NE(e.expected().find(bad.phrase), std::string::npos) << e.expected();
    EXPECT_EQ(e.where(), name + " (--set " + bad.set + ")");
    EXPECT_NE(std::string(e.what()).find("--set " + bad.set), std::string::npos) << e.what();
  }
}

TEST(SceneReader, MissingSceneFile) {
  const fs::path file = kScenes / "good" / "no_such_scene.toml";
  const InputError e = input_error([&] { read_scene(file); });
  EXPECT_EQ(e.where(), file.string());
  EXPECT_NE(e.expected().find("no such file"), std::string::npos) << e.expected();
}

TEST(SceneReader, SceneFileIsMadeAbsolute) {
  const std::string text = text_of(kScenes / "good" / "minimal_static.toml");
  const Scene s = parse_scene(text, "some/folder/scene.toml");
  EXPECT_EQ(s.file, fs::current_path() / "some" / "folder" / "scene.toml");
}

/// One row of tests/scenes/bad/CASES.md.
struct BadCase {
  std::string file, key, phrase;
  int line = 0;
};

void PrintTo(const BadCase& c, std::ostream* out) {
  *out << c.file;
}

std::string cell(std::string text) {
  const auto first = text.find_first_not_of(" `");
  const auto last = text.find_last_not_of(" `");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

/// The table of CASES.md: rows "| `file.toml` | `key` | line | `phrase` | defect |".
std::vector<BadCase> bad_cases() {
  std::vector<BadCase> cases;
  std::istringstream text(text_of(kScenes / "bad" / "CASES.md"));
  for (std::string row; std::getline(text, row);) {
    if (row.rfind("| `", 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream parts(row.substr(1));
    for (std::string part; std::getline(parts, part, '|');) cells.push_back(cell(part));
    if (cells.size() < 4) continue;
    cases.push_back({cells[0], cells[1] == "-" ? "" : cells[1], cells[3], std::stoi(cells[2])});
  }
  return cases;
}

TEST(BadScenes, CasesTableCoversEveryFile) {
  std::set<std::string> files, rows;
  for (const auto& entry : fs::directory_iterator(kScenes / "bad")) {
    if (entry.path().extension() == ".toml") files.insert(entry.path().filename().string());
  }
  for (const BadCase& c : bad_cases()) EXPECT_TRUE(rows.insert(c.file).second) << c.file;
  EXPECT_EQ(files, rows);
  EXPECT_GE(rows.size(), 20u);
}

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, IsRejectedWithKeyMessageAndLine) {
  const BadCase& c = GetParam();
  const fs::path file = kScenes / "bad" / c.file;
  const InputError e = input_error([&] { read_scene(file); });
  EXPECT_EQ(e.key(), c.key);
  EXPECT_NE(e.expected().find(c.phrase), std::string::npos) << e.expected();
  EXPECT_EQ(e.where(), file.string() + ":" + std::to_string(c.line));
  EXPECT_EQ(e.expected().rfind("expected", 0), 0u) << e.expected();
}

INSTANTIATE_TEST_SUITE_P(Cases, BadScene, ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& param) {
                           return fs::path(param.param.file).stem().string();
                         });


// ---------------------------------------------------------------------------------------------
// docs/scene.md against the reader: every key the reader accepts is documented, and every
// documented key is accepted. The reader's accepted keys are not taken from a list kept for the
// test: each table is given an unknown key, and the reader's own message ("expected one of
// ...; got unknown key") lists what it accepts there.

/// docs/scene.md's keys: under each heading "### `[name]`" (or "### `[[name]]`"), the first
/// cell of each table row, "| `key` |". The headings are the top level's keys.
std::map<std::string, std::set<std::string>> documented_keys() {
  std::ifstream in(fs::path(ROCKDD_SOURCE_DIR) / "docs" / "scene.md");
  EXPECT_TRUE(in) << "no docs/scene.md";
  const std::regex heading(R"(^#+ `\[\[?([a-z_]+)\]\]?`\s*$)"), row(R"(^\| `([a-z_0-9]+)` \|)");
  const std::regex other_heading(R"(^#+ )");
  std::map<std::string, std::set<std::string>> keys;
  std::string table;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, heading)) {
      table = m[1];
      keys[""].insert(table);
      keys[table];
    } else if (std::regex_search(line, other_heading)) {
      table.clear();
    } else if (!table.empty() && std::regex_search(line, m, row)) {
      EXPECT_TRUE(keys[table].insert(m[1]).second) << table << "." << m[1] << " twice";
    }
  }
  return keys;
}

/// The keys the reader accepts in `table` ("" for the top level), from its message about an
/// unknown key there in an otherwise valid scene.
std::set<std::string> accepted_keys(const std::string& table, bool array) {
  std::map<std::string, std::string> tables = {
      {"scene", "name = \"keys\"\n"},
      {"mesh", "shape = \"rectangle\"\nsize = [1.0, 1.0]\ndivisions = [1, 1]\n"},
      {"material", "density = 1.0\nyoung = 1.0\npoisson = 0.2\n"}};
  const std::string unknown = "zz_not_a_key = 1\n";
  std::string text = table.empty() ? unknown : "";
  if (!table.empty()) tables[table] += unknown;
  for (const auto& [name, body] : tables) {
    const bool is_array = name == "material" || (name == table && array);
    text += (is_array ? "[[" + name + "]]\n" : "[" + name + "]\n") + body;
  }
  try {
    parse_scene(text, "keys.toml");
  } catch (const InputError& e) {
    const std::string message = e.expected();
    const std::string lead = "expected one of ", tail = "; got unknown key \"zz_not_a_key\"";
    const std::size_t end = message.find(tail);
    if (message.rfind(lead, 0) != 0 || end == std::string::npos) {
      ADD_FAILURE() << table << ": " << e.what();
      return {};
    }
    EXPECT_EQ(e.key(), table.empty() ? "zz_not_a_key"
                                     : table + (array ? "[0]" : "") + ".zz_not_a_key");
    std::set<std::string> keys;
    std::stringstream list(message.substr(lead.size(), end - lead.size()));
    for (std::string key; std::getline(list, key, ',');) keys.insert(key.substr(key.find_first_not_of(' ')));
    return keys;
  }
  ADD_FAILURE() << table << ": an unknown key was accepted";
  return {};
}

TEST(SceneReference, EveryKeyTheReaderAcceptsIsDocumentedAndEveryDocumentedKeyIsAccepted) {
  const auto documented = documented_keys();
  ASSERT_TRUE(documented.count("")) << "docs/scene.md has no table headings";
  const std::set<std::string> tables = accepted_keys("", false);
  EXPECT_EQ(documented.at(""), tables) << "the top level's tables";
  const std::set<std::string> arrays = {"material", "initial", "joint", "boundary", "load",
                                        "probe"};
  int keys = 0;
  for (const std::string& table : tables) {
    SCOPED_TRACE(table);
    const std::set<std::string> accepted = accepted_keys(table, arrays.count(table) > 0);
    ASSERT_FALSE(accepted.empty());
    const auto found = documented.find(table);
    ASSERT_NE(found, documented.end()) << "docs/scene.md has no heading for [" << table << "]";
    for (const std::string& key : accepted)
      EXPECT_TRUE(found->second.count(key)) << table << "." << key << " is not in docs/scene.md";
    for (const std::string& key : found->second)
      EXPECT_TRUE(accepted.count(key)) << table << "." << key
                                       << " is in docs/scene.md but the reader refuses it";
    keys += static_cast<int>(accepted.size());
  }
  EXPECT_GE(keys, 70);  // 12 tables, 81 keys when this test was written
}

TEST(SceneReference, TheReferenceTestWouldSeeAKeyMissingFromTheDocument) {
  // The parsing above must find keys at all: a key the reader accepts is found in the page.
  const auto documented = documented_keys();
  ASSERT_TRUE(documented.count("output"));
  EXPECT_TRUE(documented.at("output").count("compress"));
  EXPECT_TRUE(documented.at("material").count("weibull_size_scaling"));
  EXPECT_FALSE(documented.at("material").count("zz_not_a_key"));
  EXPECT_EQ(accepted_keys("output", false).count("compress"), 1u);
}

}  // namespace
}  // namespace rockdd

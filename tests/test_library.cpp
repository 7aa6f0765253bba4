// The installed library's APIs (include/rockdd): the C++ handles and the C functions over
// them, linked here beside the static engine so that their results can be compared with a
// plain Simulation's. tests/consumer checks the installed package itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "engine/engine.hpp"
#include "engine/monte_carlo/monte_carlo.hpp"
#include "engine/report/run_result.hpp"
#include "rockdd/rockdd.h"
#include "rockdd/rockdd.hpp"

namespace {

const std::filesystem::path kSource = ROCKDD_SOURCE_DIR;
const std::string kCantilever1 = (kSource / "data/cantilever_model_1.toml").string();
const std::string kCantilever4 = (kSource / "data/cantilever_model_4.toml").string();
const std::string kCompression = (kSource / "data/uniaxial_compression.toml").string();

std::string read_text(const std::string& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The first Gmsh mesh of a process differs from every later one in the last bit of some
/// coordinates (about 1e-17 m on cantilever model IV; the second and third are identical): tests
/// that compare two runs bit for bit mesh once before either, so that both get a later mesh.
void mesh_once() {
  rockdd::build_scene_model(rockdd::load_scene(kCantilever1));
}

/// Settings without files on `threads` threads.
rockdd::api::RunSettings on_threads(int threads) {
  rockdd::api::RunSettings settings;
  settings.threads = threads;
  return settings;
}

// ---------------------------------------------------------------------------------------------
// C++ API

TEST(CppApi, DisplacementsAreAPlainSimulationsToTheBit) {
  const rockdd::Scene plain_scene = rockdd::load_scene(kCantilever4);
  mesh_once();
  rockdd::Simulation plain(plain_scene, rockdd::build_scene_model(plain_scene));
  rockdd::RunOptions options;
  options.write_outputs = false;
  options.threads = 2;
  ASSERT_TRUE(plain.run(options).ok);

  rockdd::api::Simulation sim(rockdd::api::Scene::from_file(kCantilever4));
  const rockdd::api::RunOutcome outcome = sim.run(on_threads(2));
  ASSERT_TRUE(outcome.ok) << outcome.reason;
  const std::span<const double> u = sim.displacements();
  const std::vector<double>& expected = plain.model().u;
  ASSERT_EQ(u.size(), expected.size());
  EXPECT_EQ(std::memcmp(u.data(), expected.data(), u.size_bytes()), 0);
  const std::span<const double> X = sim.positions();
  ASSERT_EQ(X.size(), plain.model().X.size());
  EXPECT_EQ(std::memcmp(X.data(), plain.model().X.data(), X.size_bytes()), 0);
  EXPECT_GT(u.size(), 2000u);  // 96 x 24 divisions
}

TEST(CppApi, FieldsViewTheModelsArraysWithTheirSizes) {
  rockdd::api::Simulation sim(rockdd::api::Scene::from_file(kCantilever1));
  ASSERT_TRUE(sim.run(on_threads(1)).ok);
  const auto nodes = static_cast<std::size_t>(sim.num_nodes());
  const auto elements = static_cast<std::size_t>(sim.num_elements());
  EXPECT_EQ(elements, 8u * 2u * 2u);  // divisions [8, 2], two triangles a cell
  EXPECT_EQ(sim.positions().size(), 2 * nodes);
  EXPECT_EQ(sim.displacements().size(), 2 * nodes);
  EXPECT_EQ(sim.stresses().size(), 3 * elements);
  EXPECT_EQ(sim.damage().size(), elements);
  EXPECT_EQ(sim.element_blocks().size(), elements);
  EXPECT_EQ(sim.connectivity().size(), 3 * elements);
  // Views, not copies: the same storage at every call.
  EXPECT_EQ(sim.displacements().data(), sim.displacements().data());
  EXPECT_EQ(sim.stresses().data(), sim.stresses().data());
}

TEST(CppApi, FromStringAppliesOverrides) {
  const rockdd::api::Scene scene = rockdd::api::Scene::from_string(
      read_text(kCantilever1), {"mesh.divisions=[4, 1]"}, kCantilever1);
  EXPECT_EQ(scene.name(), "cantilever-model-1");
  EXPECT_EQ(rockdd::api::Simulation(scene).num_elements(), 4 * 1 * 2);
}

TEST(CppApi, BadInputThrowsErrorOfItsKind) {
  try {
    rockdd::api::Scene::from_file(kCantilever1, {"material.0.young=-1"});
    FAIL() << "no error";
  } catch (const rockdd::api::Error& e) {
    EXPECT_EQ(e.kind(), rockdd::api::ErrorKind::bad_input);
    EXPECT_NE(std::string(e.what()).find("cantilever_model_1.toml"), std::string::npos) << e.what();
  }
}

TEST(CppApi, CallbackSeesEachStepAndStopsTheRun) {
  rockdd::api::Simulation sim(
      rockdd::api::Scene::from_file(kCompression, {"mesh.divisions=[10, 20]"}));
  std::vector<long> seen;
  const rockdd::api::RunOutcome outcome = sim.run(on_threads(1), [&](const rockdd::api::Step& s) {
    seen.push_back(s.step);
    return s.step < 3;
  });
  ASSERT_TRUE(outcome.ok) << outcome.reason;
  EXPECT_EQ(seen, (std::vector<long>{1, 2, 3}));
  const nlohmann::json summary = nlohmann::json::parse(outcome.summary_json);
  EXPECT_EQ(summary["steps"], 3);
  EXPECT_EQ(summary["stopped_by_caller"], true);
  EXPECT_THROW(sim.run(), rockdd::api::Error);  // a Simulation runs once
}

TEST(CppApi, EnsembleRunsEachSeedInProcess) {
  const rockdd::api::Scene scene = rockdd::api::Scene::from_file(
      kCompression, {"mesh.divisions=[10, 20]", "time.end=0.025"});  // 4 steps a realization
  const rockdd::api::EnsembleTable table = rockdd::api::run_ensemble(scene, 2, 7, on_threads(1));
  const rockdd::Scene engine_scene =
      rockdd::load_scene(kCompression, {"mesh.divisions=[10, 20]", "time.end=0.025"});
  EXPECT_EQ(table.columns, rockdd::ensemble_columns(engine_scene));
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0].seed, 7u);
  EXPECT_EQ(table.rows[1].seed, 8u);
  for (const rockdd::api::EnsembleRow& row : table.rows) {
    EXPECT_EQ(row.status, "ok") << row.reason;
    EXPECT_EQ(row.cells.size(), table.columns.size());
  }
  const auto steps = std::find(table.columns.begin(), table.columns.end(), "steps");
  ASSERT_NE(steps, table.columns.end());
  EXPECT_EQ(table.rows[0].cells[static_cast<std::size_t>(steps - table.columns.begin())], "4");
}

// ---------------------------------------------------------------------------------------------
// C API

TEST(CApi, BadSceneReturnsBadInputAndTheReadersMessage) {
  std::string text = read_text(kCantilever1);
  const std::size_t at = text.find("young = 10e9");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::strlen("young = 10e9"), "young = -1");
  rockdd_scene* scene = nullptr;
  EXPECT_EQ(rockdd_scene_load_string(text.c_str(), "bad_cantilever.toml", nullptr, 0, &scene),
            ROCKDD_BAD_INPUT);
  EXPECT_EQ(scene, nullptr);
  const std::string message = rockdd_last_error();
  EXPECT_NE(message.find("bad_cantilever.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("young"), std::string::npos) << message;
  EXPECT_NE(message.find("-1"), std::string::npos) << message;
}

TEST(CApi, MissingFileIsBadInputAndNullArgumentsAreRefused) {
  rockdd_scene* scene = nullptr;
  EXPECT_EQ(rockdd_scene_load_file("/nonexistent/scene.toml", nullptr, 0, &scene),
            ROCKDD_BAD_INPUT);
  EXPECT_NE(std::string(rockdd_last_error()).find("/nonexistent/scene.toml"), std::string::npos);
  EXPECT_EQ(rockdd_scene_load_file(nullptr, nullptr, 0, &scene), ROCKDD_BAD_INPUT);
  EXPECT_EQ(rockdd_run_execute(nullptr, nullptr, 1, nullptr, nullptr), ROCKDD_BAD_INPUT);
}

/// Stops the run after 3 steps; counts the calls.
int stop_after_three(long step, double time, void* user) {
  ++*static_cast<int*>(user);
  return step >= 3 ? 1 : 0;
}

TEST(CApi, StepCallbackStopsTheRunAfterThreeSteps) {
  const char* overrides[] = {"mesh.divisions=[10, 20]"};
  rockdd_scene* scene = nullptr;
  ASSERT_EQ(rockdd_scene_load_file(kCompression.c_str(), overrides, 1, &scene), ROCKDD_OK)
      << rockdd_last_error();
  rockdd_run* run = nullptr;
  ASSERT_EQ(rockdd_run_create(scene, &run), ROCKDD_OK) << rockdd_last_error();
  EXPECT_EQ(rockdd_run_summary_json(run), nullptr);
  int calls = 0;
  ASSERT_EQ(rockdd_run_execute(run, nullptr, 1, stop_after_three, &calls), ROCKDD_OK)
      << rockdd_last_error();
  EXPECT_EQ(calls, 3);
  const nlohmann::json summary = nlohmann::json::parse(rockdd_run_summary_json(run));
  EXPECT_EQ(summary["steps"], 3);
  EXPECT_EQ(summary["status"], "ok");
  const long elements = rockdd_run_num_elements(run);
  EXPECT_EQ(elements, 10 * 20 * 2);
  EXPECT_GT(rockdd_run_num_nodes(run), 0);
  EXPECT_NE(rockdd_run_displacements(run), nullptr);
  EXPECT_NE(rockdd_run_stresses(run), nullptr);
  EXPECT_NE(rockdd_run_damage(run), nullptr);
  EXPECT_NE(rockdd_run_blocks(run), nullptr);
  rockdd_run_free(run);
  rockdd_scene_free(scene);
}

TEST(CApi, FieldsMatchTheCppApi) {
  mesh_once();
  rockdd_scene* scene = nullptr;
  ASSERT_EQ(rockdd_scene_load_file(kCantilever1.c_str(), nullptr, 0, &scene), ROCKDD_OK);
  rockdd_run* run = nullptr;
  ASSERT_EQ(rockdd_run_create(scene, &run), ROCKDD_OK);
  ASSERT_EQ(rockdd_run_execute(run, nullptr, 1, nullptr, nullptr), ROCKDD_OK);
  rockdd::api::Simulation sim(rockdd::api::Scene::from_file(kCantilever1));
  ASSERT_TRUE(sim.run(on_threads(1)).ok);
  ASSERT_EQ(rockdd_run_num_nodes(run), sim.num_nodes());
  EXPECT_EQ(std::memcmp(rockdd_run_displacements(run), sim.displacements().data(),
                        sim.displacements().size_bytes()),
            0);
  EXPECT_EQ(std::string(rockdd_version()), rockdd::api::version());
  rockdd_run_free(run);
  rockdd_scene_free(scene);
}

TEST(CApi, ConnectivityRebuildsTheMeshOfTheCppApiAndOfTheModel) {
  // A C caller rebuilds the mesh from the positions and the connectivity: after a run whose
  // fracture split nodes (the displacement-controlled disk splits in two, under 1 s), the
  // triangles are the model's, each counter-clockwise at the reference positions, and every
  // node is used.
  rockdd_scene* scene = nullptr;
  const std::string disk = (kSource / "data/brazilian_disk_displacement.toml").string();
  ASSERT_EQ(rockdd_scene_load_file(disk.c_str(), nullptr, 0, &scene), ROCKDD_OK)
      << rockdd_last_error();
  rockdd_run* run = nullptr;
  ASSERT_EQ(rockdd_run_create(scene, &run), ROCKDD_OK) << rockdd_last_error();
  EXPECT_EQ(rockdd_run_connectivity(nullptr), nullptr);
  const long nodes_before = rockdd_run_num_nodes(run);
  ASSERT_EQ(rockdd_run_execute(run, nullptr, 1, nullptr, nullptr), ROCKDD_OK)
      << rockdd_last_error();
  const long nodes = rockdd_run_num_nodes(run), elements = rockdd_run_num_elements(run);
  const int32_t* conn = rockdd_run_connectivity(run);
  const double* X = rockdd_run_positions(run);
  ASSERT_NE(conn, nullptr);
  std::vector<int> used(static_cast<std::size_t>(nodes), 0);
  long counter_clockwise = 0;
  for (long e = 0; e < elements; ++e) {
    const int32_t a = conn[3 * e], b = conn[3 * e + 1], c = conn[3 * e + 2];
    ASSERT_TRUE(a >= 0 && a < nodes && b >= 0 && b < nodes && c >= 0 && c < nodes) << e;
    for (const int32_t n : {a, b, c}) used[static_cast<std::size_t>(n)] = 1;
    const double area2 = (X[2 * b] - X[2 * a]) * (X[2 * c + 1] - X[2 * a + 1]) -
                         (X[2 * c] - X[2 * a]) * (X[2 * b + 1] - X[2 * a + 1]);
    counter_clockwise += area2 > 0;
  }
  EXPECT_EQ(counter_clockwise, elements);
  EXPECT_EQ(std::count(used.begin(), used.end(), 1), nodes);
  // The same run through the C++ API: the same triangles.
  rockdd::api::Simulation sim(rockdd::api::Scene::from_file(disk));
  ASSERT_TRUE(sim.run(on_threads(1)).ok);
  ASSERT_EQ(sim.connectivity().size(), static_cast<std::size_t>(3 * elements));
  EXPECT_EQ(std::memcmp(conn, sim.connectivity().data(), sim.connectivity().size_bytes()), 0);
  const nlohmann::json summary = nlohmann::json::parse(rockdd_run_summary_json(run));
  EXPECT_GT(summary["damaged_elements"].get<long>(), 0);
  // The crack split nodes: the C caller must take the arrays again after the run.
  EXPECT_GT(nodes, nodes_before) << "the run split no node; the test would not see a stale mesh";
  rockdd_run_free(run);
  rockdd_scene_free(scene);
}

TEST(CApi, EnsembleTableIsTheCppApisRowForRow) {
  const char* overrides[] = {"mesh.divisions=[10, 20]", "time.end=0.025"};  // 4 steps each
  rockdd_scene* scene = nullptr;
  ASSERT_EQ(rockdd_scene_load_file(kCompression.c_str(), overrides, 2, &scene), ROCKDD_OK)
      << rockdd_last_error();
  const uint64_t first = 7;
  rockdd_ensemble* table = nullptr;
  ASSERT_EQ(rockdd_ensemble_run(scene, 2, &first, nullptr, 1, &table), ROCKDD_OK)
      << rockdd_last_error();
  const rockdd::api::EnsembleTable expected = rockdd::api::run_ensemble(
      rockdd::api::Scene::from_file(kCompression, {"mesh.divisions=[10, 20]", "time.end=0.025"}),
      2, 7, on_threads(1));
  ASSERT_EQ(rockdd_ensemble_num_columns(table), expected.columns.size());
  for (std::size_t c = 0; c < expected.columns.size(); ++c) {
    EXPECT_EQ(rockdd_ensemble_column(table, c), expected.columns[c]);
    EXPECT_EQ(rockdd_ensemble_column_index(table, expected.columns[c].c_str()),
              static_cast<long>(c));
  }
  EXPECT_EQ(rockdd_ensemble_column(table, expected.columns.size()), nullptr);
  EXPECT_EQ(rockdd_ensemble_column_index(table, "no.such.column"), -1);
  ASSERT_EQ(rockdd_ensemble_num_rows(table), 2u);
  const long steps = rockdd_ensemble_column_index(table, "steps");
  ASSERT_GE(steps, 0);
  for (std::size_t r = 0; r < 2; ++r) {
    EXPECT_EQ(rockdd_ensemble_seed(table, r), 7u + r);
    EXPECT_STREQ(rockdd_ensemble_status(table, r), "ok");
    EXPECT_STREQ(rockdd_ensemble_reason(table, r), "");
    for (std::size_t c = 0; c < expected.columns.size(); ++c) {
      if (expected.columns[c] == "wall_seconds") continue;
      EXPECT_EQ(rockdd_ensemble_cell(table, r, c), expected.rows[r].cells[c]) << c;
    }
    EXPECT_EQ(rockdd_ensemble_value(table, r, static_cast<std::size_t>(steps)), 4.0);
  }
  // An empty cell (peaks come from files, and there are none) reads as NaN; out of range too.
  const long peak = rockdd_ensemble_column_index(table, "peaks.top.fy");
  ASSERT_GE(peak, 0);
  EXPECT_STREQ(rockdd_ensemble_cell(table, 0, static_cast<std::size_t>(peak)), "");
  EXPECT_TRUE(std::isnan(rockdd_ensemble_value(table, 0, static_cast<std::size_t>(peak))));
  EXPECT_TRUE(std::isnan(rockdd_ensemble_value(table, 2, 0)));
  EXPECT_EQ(rockdd_ensemble_status(table, 2), nullptr);
  rockdd_ensemble_free(table);

  // A homogeneous scene has no seeds to vary: bad input, with the reader's reason.
  rockdd_scene* plain = nullptr;
  ASSERT_EQ(rockdd_scene_load_file(kCantilever1.c_str(), nullptr, 0, &plain), ROCKDD_OK);
  rockdd_ensemble* none = nullptr;
  EXPECT_EQ(rockdd_ensemble_run(plain, 2, nullptr, nullptr, 1, &none), ROCKDD_BAD_INPUT);
  EXPECT_NE(std::string(rockdd_last_error()).find("heterogeneous"), std::string::npos)
      << rockdd_last_error();
  EXPECT_EQ(none, nullptr);
  EXPECT_EQ(rockdd_ensemble_run(scene, 0, nullptr, nullptr, 1, &none), ROCKDD_BAD_INPUT);
  EXPECT_EQ(rockdd_ensemble_run(nullptr, 2, nullptr, nullptr, 1, &none), ROCKDD_BAD_INPUT);
  rockdd_ensemble_free(nullptr);
  rockdd_scene_free(plain);
  rockdd_scene_free(scene);
}

}  // namespace

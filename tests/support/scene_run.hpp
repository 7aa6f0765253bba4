#pragma once
// Reading a scene from TOML text and running a scene in a scratch folder, for engine tests.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "csv_columns.hpp"
#include "data_file.hpp"
#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"
#include "engine/scene/scene_reader.hpp"
#include "temp_dir.hpp"

namespace rockdd::test {

/// A scene from TOML text, as if read from `dir/scene.toml` (written there too).
inline Scene scene_from_text(const std::string& text, const std::filesystem::path& dir,
                             const std::vector<std::string>& overrides = {}) {
  const auto file = dir / "scene.toml";
  std::ofstream(file) << text;
  return read_scene(file, overrides);
}

/// What a test run leaves: the final model, the result and history.csv by column.
struct SceneRun {
  Model model;
  RunResult result;
  CsvColumns history;
  std::map<std::string, Model> at_event;  // the model at each run event (first_damage, ...)
};

/// Runs `scene` with its outputs under `dir`/out.
inline SceneRun run_scene(const Scene& scene, const std::filesystem::path& dir, int threads) {
  Simulation sim(scene, build_scene_model(scene));
  RunOptions options;
  options.out_root = dir / "out";
  options.threads = threads;
  std::map<std::string, Model> at_event;
  options.on_event = [&](const RunEvent& event, const Model& model) {
    at_event.emplace(event.name, model);
  };
  SceneRun run{{}, sim.run(options), {}, std::move(at_event)};
  run.model = sim.model();
  run.history = read_csv(dir / "out" / scene.name / "history.csv");
  return run;
}

/// Runs a scene given as TOML text in a temporary folder (with `files` written beside it).
inline SceneRun run_scene_text(const std::string& text,
                               const std::vector<std::string>& overrides = {}, int threads = 0,
                               const std::map<std::string, std::string>& files = {}) {
  TempDir dir;
  for (const auto& [name, content] : files) std::ofstream(dir.path() / name) << content;
  return run_scene(scene_from_text(text, dir.path(), overrides), dir.path(), threads);
}

/// Runs a scene of data/ with `overrides` in a temporary folder.
inline SceneRun run_data_scene(const std::string& name,
                               const std::vector<std::string>& overrides = {}, int threads = 0) {
  TempDir dir;
  Scene scene = read_scene(data_file(name), overrides);
  return run_scene(scene, dir.path(), threads);
}

}  // namespace rockdd::test

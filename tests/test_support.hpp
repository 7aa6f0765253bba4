#pragma once
// Helpers shared by the engine tests: scenes from TOML text, temporary folders, CSV reading.
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"
#include "engine/scene/scene_reader.hpp"

namespace rockdd::test {

/// A fresh folder under the system temp dir, removed at destruction.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("rockdd-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// A scene from TOML text, as if read from `dir/scene.toml` (written there too).
inline Scene scene_from_text(const std::string& text, const std::filesystem::path& dir,
                             const std::vector<std::string>& overrides = {}) {
  const auto file = dir / "scene.toml";
  std::ofstream(file) << text;
  return read_scene(file, overrides);
}

/// What a test run leaves: the final model, the result, history.csv by column, and the model
/// at each run event (first_damage, first_separation).
struct SceneRun {
  Model model;
  RunResult result;
  std::map<std::string, std::vector<double>> history;
  std::map<std::string, Model> at_event;
};

inline std::map<std::string, std::vector<double>> read_csv(const std::filesystem::path& file);

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

inline std::filesystem::path data_file(const std::string& name);

/// Runs a scene of data/ with `overrides` in a temporary folder.
inline SceneRun run_data_scene(const std::string& name,
                               const std::vector<std::string>& overrides = {}, int threads = 0) {
  TempDir dir;
  Scene scene = read_scene(data_file(name), overrides);
  return run_scene(scene, dir.path(), threads);
}

/// Gmsh lines for an axis-aligned rectangle [x0, x1] x [y0, y1] of element size `size`, as
/// surface `id` (points, lines and loop numbered id + 1 .. id + 4): bottom is line id + 1,
/// right id + 2, top id + 3, left id + 4.
inline std::string rectangle_geo(int id, double x0, double y0, double x1, double y1, double size) {
  auto num = [](double v) { return std::to_string(v); };
  auto n = [&](int k) { return std::to_string(id + k); };
  const std::string s = num(size);
  return "Point(" + n(1) + ") = {" + num(x0) + ", " + num(y0) + ", 0, " + s + "};\n" + "Point(" +
         n(2) + ") = {" + num(x1) + ", " + num(y0) + ", 0, " + s + "};\n" + "Point(" + n(3) +
         ") = {" + num(x1) + ", " + num(y1) + ", 0, " + s + "};\n" + "Point(" + n(4) + ") = {" +
         num(x0) + ", " + num(y1) + ", 0, " + s + "};\n" + "Line(" + n(1) + ") = {" + n(1) + ", " +
         n(2) + "};\nLine(" + n(2) + ") = {" + n(2) + ", " + n(3) + "};\nLine(" + n(3) + ") = {" +
         n(3) + ", " + n(4) + "};\nLine(" + n(4) + ") = {" + n(4) + ", " + n(1) + "};\n" +
         "Curve Loop(" + n(1) + ") = {" + n(1) + ", " + n(2) + ", " + n(3) + ", " + n(4) +
         "};\nPlane Surface(" + n(1) + ") = {" + n(1) + "};\n";
}

/// A scene file from data/.
inline std::filesystem::path data_file(const std::string& name) {
  return std::filesystem::path(ROCKDD_SOURCE_DIR) / "data" / name;
}

/// What the rockdd command line printed (stdout and stderr together) and its exit status.
struct Invocation {
  int exit_code = -1;
  std::string output;
};

/// Runs a shell command line, stdout and stderr together.
inline Invocation run_shell(const std::string& command) {
  Invocation inv;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) inv.output += buffer.data();
  const int status = pclose(pipe);
  inv.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return inv;
}

/// Runs `rockdd ARGS` in `cwd`; with `timeout_s` > 0 it is killed after that many seconds
/// (exit status 124), so that a hang fails the test instead of stalling the suite.
inline Invocation rockdd_cli(const std::string& args, const std::filesystem::path& cwd,
                             int timeout_s = 0) {
  const std::string limit =
      timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : std::string();
  return run_shell("cd '" + cwd.string() + "' && " + limit + "'" + ROCKDD_BINARY + "' " + args +
                   " 2>&1");
}

/// A CSV file as named columns of numbers.
inline std::map<std::string, std::vector<double>> read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) names.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t i = 0;
    for (std::string cell; std::getline(row, cell, ',') && i < names.size(); ++i)
      columns[names[i]].push_back(std::stod(cell));
  }
  return columns;
}

/// The whole content of a file.
inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace rockdd::test

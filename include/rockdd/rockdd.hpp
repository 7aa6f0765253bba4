#pragma once
// rockdd's installed C++ API (librockdd, `find_package(rockdd)` -> rockdd::engine). It names no
// Eigen, CHOLMOD or TBB type: a scene and a simulation are handles over the engine's own.
//
//   using namespace rockdd::api;
//   Scene scene = Scene::from_file("cantilever.toml", {"mesh.divisions=[16, 4]"});
//   Simulation sim(scene);
//   sim.run({}, [](const Step& s) { return s.step < 100; });  // false stops the run
//   std::span<const double> u = sim.displacements();        // 2 per node, no copy
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rockdd/export.h"

namespace rockdd::api {

/// What went wrong: bad input (a scene key, a file; exit 2 on the command line), a numerical
/// failure (exit 1), or anything else.
enum class ErrorKind { bad_input, run_failed, error };

/// The one exception the API throws; what() is the engine's message (file, key, expected).
class ROCKDD_API Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message);
  ~Error() override;
  ErrorKind kind() const { return kind_; }

 private:
  ErrorKind kind_;
};

/// A read and validated scene. Cheap to keep; a Simulation copies what it needs.
class ROCKDD_API Scene {
 public:
  /// Reads `path`, after `overrides` ("key.path=value", as `rockdd run --set`). Throws Error.
  static Scene from_file(const std::string& path, const std::vector<std::string>& overrides = {});
  /// Reads TOML `text`; `name` stands for the file in messages and anchors relative paths
  /// (mesh files). Throws Error.
  static Scene from_string(std::string_view text, const std::vector<std::string>& overrides = {},
                           const std::string& name = "scene.toml");
  ~Scene();
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  /// The scene's [scene].name.
  std::string name() const;

 private:
  struct Impl;
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend struct SceneAccess;  // the library's own files reach the engine's scene
};

/// What a step callback sees after each committed step.
struct Step {
  long step = 0;
  double time = 0, dt = 0, end_time = 0;
};

/// Called after each committed step; returning false ends the run there (ok, summary
/// "stopped_by_caller"). The simulation's fields may be read inside it.
using StepCallback = std::function<bool(const Step&)>;

/// Where a run writes and how many threads it uses.
struct RunSettings {
  std::string out_dir;        // the run folder; empty: no files (the summary comes regardless)
  int threads = 0;            // 0: every hardware thread
  bool write_frames = false;  // VTU frames besides history.csv, profiles and summary.json
};

/// How a run ended, and its summary.json.
struct RunOutcome {
  bool ok = false;
  std::string reason;        // why it failed; empty when ok
  std::string summary_json;  // the summary.json content (also without out_dir)
};

/// One simulation of a scene: meshing and model set-up happen at construction.
class ROCKDD_API Simulation {
 public:
  /// Meshes the scene and builds its model. Throws Error (bad_input) for a scene the model
  /// cannot satisfy (unknown names, a mesh file missing).
  explicit Simulation(const Scene& scene);
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;

  /// Runs to the end, or until `on_step` returns false. A numerical failure is an outcome
  /// (ok = false), not an exception.
  RunOutcome run(const RunSettings& settings = {}, const StepCallback& on_step = {});

  std::int32_t num_nodes() const;
  std::int32_t num_elements() const;
  /// Views of the engine's own arrays (no copies), valid until the next run or destruction;
  /// fracture adds nodes, so take them again after a run. Reference positions (x, y per node).
  std::span<const double> positions() const;
  /// Displacements (ux, uy per node).
  std::span<const double> displacements() const;
  /// Element stresses (sxx, syy, sxy per element, Pa).
  std::span<const double> stresses() const;
  /// Element damage w in [0, 1].
  std::span<const double> damage() const;
  /// Block id of each element (fracture splits blocks).
  std::span<const std::int32_t> element_blocks() const;
  /// Element connectivity (3 node ids per element, counter-clockwise).
  std::span<const std::int32_t> connectivity() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One realization of an ensemble: a row of `rockdd mc`'s mc.csv.
struct EnsembleRow {
  std::uint64_t seed = 0;
  std::string status;              // "ok" or "failed"
  std::vector<std::string> cells;  // the columns' values as mc.csv writes them; "": none
  std::string reason;
};

/// An ensemble's table: the columns (as ensemble_columns names them) and one row per seed.
struct EnsembleTable {
  std::vector<std::string> columns;
  std::vector<EnsembleRow> rows;
};

/// Runs `realizations` seeds of `scene` (from `first_seed`, default the scene's) one after the
/// other in this process, as `rockdd mc` does in workers; with `settings.out_dir` each leaves
/// its files in <out_dir>/seed_<seed> (the peaks.* columns come from those outputs and are
/// empty without). Throws Error when the scene has no heterogeneous material.
ROCKDD_API EnsembleTable run_ensemble(const Scene& scene, long realizations,
                                      std::optional<std::uint64_t> first_seed = std::nullopt,
                                      const RunSettings& settings = {});

/// The rockdd version string.
ROCKDD_API const char* version();

}  // namespace rockdd::api

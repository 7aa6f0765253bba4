#pragma once
// The files of one run in its folder (<out>/<scene name>/ by default): history.csv, frames/
// with frames.pvd, profiles/, summary.json. Every file appears complete or not at all.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/common/atomic_file.hpp"
#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// Energy totals over the thickness (J), the last history columns.
struct EnergyBalance {
  double kinetic = 0, strain = 0, external_work = 0, dissipated = 0;
  double snap_back = 0;   // released by re-settling after damage, without inertia (J)
  double integrator = 0;  // damped by the time integrator, with inertia (J)
  double anchor = 0;      // held by the fragment restraint when steps ended (J)
  double quasi_static = 0;  // taken by the mass term of steps without inertia (J)
  double initial = 0;       // kinetic and strain energy at step 0 (J)

  /// The energy put in (the initial energy and the work) less everything it went into: what
  /// the balance does not account for (J).
  double unaccounted() const {
    return initial + external_work - kinetic - strain - dissipated - snap_back - integrator - anchor -
           quasi_static;
  }
};

/// Writes the run's files; history.csv appears only through finish(): a run that dies
/// without finishing leaves no history that could pass for a complete one.
class RunOutputs {
 public:
  /// Creates the run folder `dir` (and frames/, profiles/ when needed) and starts history.csv.
  /// Without `frames`, frame() writes nothing (rockdd mc's default: an ensemble's VTU files
  /// would dwarf its tables).
  RunOutputs(const Scene& scene, const std::filesystem::path& dir,
             const std::vector<std::string>& probe_columns, bool line_probes, bool frames = true);
  ~RunOutputs();
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  /// Appends one history row and updates the probe peaks.
  void history_row(long step, double time, double dt, const std::vector<double>& probe_values,
                   const EnergyBalance& energy);
  /// Writes frames/frame_<step>.vtu with the scene's output fields, and rewrites frames.pvd
  /// (nothing when frames are off). With the scene's output.last_frame_only (rockdd mc), the
  /// frame is only kept, replacing the one kept before, and finish() writes the last.
  void frame(const Model& model, long step, double time);
  /// Writes events/<event>.vtu, the state after the damage pass of a run event (not part of
  /// frames.pvd: it lies inside a step), and returns its path in the run folder; empty when
  /// frames are off or only the last is kept (output.last_frame_only).
  std::string event_frame(const Model& model, const std::string& event);
  /// Largest magnitude seen of each probe column.
  const std::map<std::string, double>& peaks() const { return peaks_; }
  /// Run folder.
  const std::filesystem::path& dir() const { return dir_; }
  /// Commits history.csv, writes the kept last frame (output.last_frame_only) and
  /// summary.json.
  void finish(const nlohmann::json& summary);

  /// Observes each history row as it is written: the command line's progress line follows
  /// the column that ends a run on softening through it. Per thread: the rows of the runs
  /// this thread makes from now on (an empty function stops it).
  using RowObserver = std::function<void(long step, const std::vector<std::string>& columns,
                                         const std::vector<double>& values)>;
  static void observe_rows(RowObserver observer);

 private:
  /// The arrays of one frame, copied from the model.
  struct Frame {
    long step = 0;
    double time = 0.0;
    std::vector<double> points, displacement, velocity, stress, strain, principal, damage;
    std::vector<std::int32_t> triangles, block, material;
  };
  bool wants(std::string_view field) const;  // an output.fields entry
  Frame capture(const Model& model, long step, double time) const;
  /// Writes `file` with the scene's output fields of `frame`.
  void write_arrays(const Frame& frame, const std::filesystem::path& file) const;
  /// Writes frames/frame_<step>.vtu and rewrites frames.pvd.
  void write_frame(const Frame& frame);

  std::filesystem::path dir_;
  std::vector<std::string> fields_;
  std::vector<std::string> columns_;
  std::map<std::string, double> peaks_;
  std::unique_ptr<AtomicFile> history_;
  std::vector<std::pair<double, std::string>> frames_;
  bool write_frames_ = true;
  bool last_frame_only_ = false;
  bool compress_ = true;
  std::optional<Frame> kept_;  // last_frame_only: the latest frame, written by finish()
};

}  // namespace rockdd

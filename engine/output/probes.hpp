#pragma once
// Probes: the scene's named measurements, as history.csv columns and line profiles.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/scene/scene.hpp"

namespace rockdd {

/// A line-probe sample: where it lies in the reference mesh.
struct LineSample {
  double s = 0.0, x = 0.0, y = 0.0;  // distance along the segment, position
  std::int32_t element = -1;
  double bary[3] = {0.0, 0.0, 0.0};  // barycentric weights of the element's nodes
};

/// Probes resolved against one model: nodes, bodies and line samples found once at t = 0.
class Probes {
 public:
  /// Resolves every probe; throws InputError naming `probe[i]` for unknown names.
  Probes(const Scene& scene, const Model& model);

  /// History column names, "<probe>.<field>", in scene order (line probes have none).
  const std::vector<std::string>& columns() const { return columns_; }
  /// Appends the current value of every column to `row`. `reaction` is the force the
  /// constraints exert on each dof (2 per node). Updates cumulative body rotations.
  void evaluate(const Model& model, std::span<const double> reaction, std::vector<double>& row);
  /// After fracture split nodes, a fresh Probes resolves the new nodes; this keeps what the
  /// old one had accumulated (cumulative body rotations, located line samples).
  void carry_state_from(const Probes& old);
  /// Whether any probe is a line probe.
  bool has_line_probes() const;
  /// Writes profiles/<probe>_<step>.csv for every line probe (atomically). The samples are
  /// located in the reference mesh on the first call: a run without outputs never pays it.
  void write_profiles(const Model& model, const std::filesystem::path& dir, long step);

 private:
  struct Resolved {
    const ProbeSpec* spec;
    std::vector<std::int32_t> nodes;  // point: 1 node; curve/body: its nodes
    std::vector<LineSample> samples;  // line, located on first use
    bool located = false;
    std::vector<double> ref_centered;  // body: reference positions minus centroid
    double rotation = 0.0;             // body: cumulative rotation (rad)
    std::int32_t body = -1;            // body: index, -1 = every body
  };
  std::vector<Resolved> probes_;
  std::vector<std::string> columns_;
};

}  // namespace rockdd

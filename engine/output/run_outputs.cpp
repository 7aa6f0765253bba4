#include "engine/output/run_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/common/number_format.hpp"
#include "engine/output/vtu_writer.hpp"
#include "kernels/principal.hpp"

namespace rockdd {

RunOutputs::RunOutputs(const Scene& scene, const std::filesystem::path& dir,
                       const std::vector<std::string>& probe_columns, bool line_probes, bool frames)
    : dir_(dir), fields_(scene.output.fields), columns_(probe_columns), write_frames_(frames) {
  // Frames and profiles of an earlier run in the same folder would mix with this run's (a
  // longer earlier run leaves frames past this one's end): they are removed first.
  for (const char* folder : {"frames", "profiles", "events"}) {
    std::error_code ignored;
    if (std::filesystem::is_directory(dir_ / folder, ignored))
      for (const auto& entry : std::filesystem::directory_iterator(dir_ / folder, ignored)) {
        const std::string name = entry.path().filename().string();
        const bool ours = (name.starts_with("frame_") && name.ends_with(".vtu")) ||
                          (std::string(folder) == "profiles" && name.ends_with(".csv")) ||
                          (std::string(folder) == "events" && name.ends_with(".vtu"));
        if (ours) std::filesystem::remove(entry.path(), ignored);
      }
  }
  if (write_frames_) {
    std::filesystem::create_directories(dir_ / "frames");
  } else {
    // An earlier run's frames were just removed: their list goes too, and their folder
    // unless something else is in it.
    std::error_code ignored;
    std::filesystem::remove(dir_ / "frames.pvd", ignored);
    std::filesystem::remove(dir_ / "frames", ignored);
    std::filesystem::create_directories(dir_);
  }
  {
    std::error_code ignored;
    std::filesystem::remove(dir_ / "events", ignored);  // only if empty: events come when due
  }
  if (line_probes) std::filesystem::create_directories(dir_ / "profiles");
  history_ = std::make_unique<AtomicFile>(dir_ / "history.csv");
  auto& out = history_->stream();
  out << "step,time,dt";
  for (const auto& c : columns_) out << ',' << c;
  out << ",energy.kinetic,energy.strain,energy.external_work,energy.dissipated,energy.snap_back,"
         "energy.integrator\n";
}

RunOutputs::~RunOutputs() = default;

void RunOutputs::history_row(long step, double time, double dt,
                             const std::vector<double>& probe_values, const EnergyBalance& energy) {
  auto& out = history_->stream();
  out << step << ',' << format_number(time) << ',' << format_number(dt);
  for (std::size_t i = 0; i < probe_values.size(); ++i) {
    out << ',' << format_number(probe_values[i]);
    double& peak = peaks_[columns_[i]];
    peak = std::max(peak, std::abs(probe_values[i]));
  }
  for (const double e : {energy.kinetic, energy.strain, energy.external_work, energy.dissipated,
                         energy.snap_back, energy.integrator})
    out << ',' << format_number(e);
  out << '\n';
}

void RunOutputs::frame(const Model& model, long step, double time) {
  if (!write_frames_) return;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05ld.vtu", step);
  write_fields(model, dir_ / "frames" / name);
  frames_.emplace_back(time, std::string("frames/") + name);
  write_pvd(dir_ / "frames.pvd", frames_);
}

std::string RunOutputs::event_frame(const Model& model, const std::string& event) {
  if (!write_frames_) return {};
  std::filesystem::create_directories(dir_ / "events");
  const std::string path = "events/" + event + ".vtu";
  write_fields(model, dir_ / path);
  return path;
}

void RunOutputs::write_fields(const Model& model, const std::filesystem::path& file) const {
  const auto num_nodes = static_cast<std::size_t>(model.num_nodes());
  const auto num_elements = static_cast<std::size_t>(model.num_elements());
  std::vector<double> points(2 * num_nodes);
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = model.X[i] + model.u[i];
  // Vectors get a zero z so ParaView's "Warp By Vector" and glyphs work on them directly.
  auto as_3d = [&](const std::vector<double>& field) {
    std::vector<double> out(3 * num_nodes, 0.0);
    for (std::size_t n = 0; n < num_nodes; ++n) {
      out[3 * n] = field[2 * n];
      out[3 * n + 1] = field[2 * n + 1];
    }
    return out;
  };
  auto wants = [&](const char* f) {
    return std::find(fields_.begin(), fields_.end(), f) != fields_.end();
  };
  std::vector<double> displacement, velocity, principal;
  std::vector<VtuArray> point_data, cell_data;
  if (wants("displacement")) {
    displacement = as_3d(model.u);
    point_data.push_back({"displacement", 3, displacement, {}});
  }
  if (wants("velocity")) {
    velocity = as_3d(model.v);
    point_data.push_back({"velocity", 3, velocity, {}});
  }
  if (wants("stress")) cell_data.push_back({"stress", 3, model.stress, {}});
  if (wants("strain")) cell_data.push_back({"strain", 3, model.strain, {}});
  if (wants("principal") || wants("stress")) {
    principal.resize(2 * num_elements);
    for (std::size_t e = 0; e < num_elements; ++e)
      kernels::principal_values(model.stress[3 * e], model.stress[3 * e + 1],
                                model.stress[3 * e + 2], principal[2 * e], principal[2 * e + 1]);
    cell_data.push_back({"principal", 2, principal, {}});
  }
  if (wants("damage")) cell_data.push_back({"damage", 1, model.damage, {}});
  if (wants("block")) cell_data.push_back({"block", 1, {}, model.element_block});
  if (wants("material")) cell_data.push_back({"material", 1, {}, model.element_material});

  write_vtu(file, points, model.conn, point_data, cell_data);
}

void RunOutputs::finish(const nlohmann::json& summary) {
  if (history_) {
    history_->commit();
    history_.reset();
  }
  write_file_atomically(dir_ / "summary.json", summary.dump(2) + "\n");
}

}  // namespace rockdd

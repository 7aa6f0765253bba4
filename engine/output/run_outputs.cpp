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
    : dir_(dir),
      fields_(scene.output.fields),
      columns_(probe_columns),
      write_frames_(frames),
      last_frame_only_(scene.output.last_frame_only),
      compress_(scene.output.compress) {
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
         "energy.integrator,energy.anchor_work,energy.quasi_static_loss,energy.unaccounted\n";
}

RunOutputs::~RunOutputs() = default;

namespace {
thread_local RunOutputs::RowObserver row_observer;
}

void RunOutputs::observe_rows(RowObserver observer) {
  row_observer = std::move(observer);
}

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
                         energy.snap_back, energy.integrator, energy.anchor, energy.quasi_static,
                         energy.unaccounted()})
    out << ',' << format_number(e);
  out << '\n';
  if (row_observer) row_observer(step, columns_, probe_values);
}

bool RunOutputs::wants(std::string_view field) const {
  return std::find(fields_.begin(), fields_.end(), field) != fields_.end();
}

std::string RunOutputs::event_frame(const Model& model, const std::string& event) {
  if (!write_frames_ || last_frame_only_) return {};  // rockdd mc keeps the last frame only
  std::filesystem::create_directories(dir_ / "events");
  const std::string path = "events/" + event + ".vtu";
  write_arrays(capture(model, 0, 0.0), dir_ / path);
  return path;
}

RunOutputs::Frame RunOutputs::capture(const Model& model, long step, double time) const {
  const auto num_nodes = static_cast<std::size_t>(model.num_nodes());
  const auto num_elements = static_cast<std::size_t>(model.num_elements());
  Frame f;
  f.step = step;
  f.time = time;
  f.points.resize(2 * num_nodes);
  for (std::size_t i = 0; i < f.points.size(); ++i) f.points[i] = model.X[i] + model.u[i];
  f.triangles = model.conn;
  // Vectors get a zero z so ParaView's "Warp By Vector" and glyphs work on them directly.
  auto as_3d = [&](const std::vector<double>& field) {
    std::vector<double> out(3 * num_nodes, 0.0);
    for (std::size_t n = 0; n < num_nodes; ++n) {
      out[3 * n] = field[2 * n];
      out[3 * n + 1] = field[2 * n + 1];
    }
    return out;
  };
  if (wants("displacement")) f.displacement = as_3d(model.u);
  if (wants("velocity")) f.velocity = as_3d(model.v);
  if (wants("stress")) f.stress = model.stress;
  if (wants("strain")) f.strain = model.strain;
  if (wants("principal") || wants("stress")) {
    f.principal.resize(2 * num_elements);
    for (std::size_t e = 0; e < num_elements; ++e)
      kernels::principal_values(model.stress[3 * e], model.stress[3 * e + 1],
                                model.stress[3 * e + 2], f.principal[2 * e],
                                f.principal[2 * e + 1]);
  }
  if (wants("damage")) f.damage = model.damage;
  if (wants("block")) f.block = model.element_block;
  if (wants("material")) f.material = model.element_material;
  return f;
}

void RunOutputs::write_arrays(const Frame& f, const std::filesystem::path& file) const {
  // Component names: ParaView shows them in its colouring menu (and no meaningless
  // "Magnitude" of a stress tensor's three components is taken for a vector's).
  const std::vector<std::string> xyz{"x", "y", "z"}, tensor{"xx", "yy", "xy"};
  std::vector<VtuArray> point_data, cell_data;
  if (wants("displacement"))
    point_data.push_back({"displacement", 3, f.displacement, {}, xyz});
  if (wants("velocity")) point_data.push_back({"velocity", 3, f.velocity, {}, xyz});
  if (wants("stress")) cell_data.push_back({"stress", 3, f.stress, {}, tensor});
  if (wants("strain"))
    cell_data.push_back({"strain", 3, f.strain, {}, {"xx", "yy", "gamma_xy"}});
  // The in-plane principal stresses, major then minor (tension positive): s1 >= s3.
  if (wants("principal") || wants("stress"))
    cell_data.push_back({"principal", 2, f.principal, {}, {"s1", "s3"}});
  if (wants("damage")) cell_data.push_back({"damage", 1, f.damage, {}});
  if (wants("block")) cell_data.push_back({"block", 1, {}, f.block});
  if (wants("material")) cell_data.push_back({"material", 1, {}, f.material});

  VtuEncoding encoding;
  encoding.compress = compress_;
  write_vtu(file, f.points, f.triangles, point_data, cell_data, encoding);
}

void RunOutputs::write_frame(const Frame& f) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05ld.vtu", f.step);
  write_arrays(f, dir_ / "frames" / name);
  frames_.emplace_back(f.time, std::string("frames/") + name);
  write_pvd(dir_ / "frames.pvd", frames_);
}

void RunOutputs::frame(const Model& model, long step, double time) {
  if (!write_frames_) return;
  if (last_frame_only_) {
    kept_ = capture(model, step, time);
    return;
  }
  write_frame(capture(model, step, time));
}

void RunOutputs::finish(const nlohmann::json& summary) {
  if (kept_) {
    write_frame(*kept_);
    kept_.reset();
  }
  if (history_) {
    history_->commit();
    history_.reset();
  }
  write_file_atomically(dir_ / "summary.json", summary.dump(2) + "\n");
}

}  // namespace rockdd

#include <memory>

#include "engine/engine.hpp"
#include "engine/report/run_result.hpp"
#include "library/api_errors.hpp"
#include "library/scene_impl.hpp"

namespace rockdd::api {

struct Simulation::Impl {
  std::unique_ptr<rockdd::Simulation> simulation;
  bool ran = false;
};

namespace {

/// The engine's options for `settings`: files only where the caller named a folder.
RunOptions run_options(const RunSettings& settings) {
  RunOptions options;
  options.out_dir = settings.out_dir;
  options.write_outputs = !settings.out_dir.empty();
  options.write_frames = settings.write_frames;
  options.threads = settings.threads;
  return options;
}

}  // namespace

Simulation::Simulation(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  translate_errors([&] {
    const rockdd::Scene& s = SceneAccess::scene(scene);
    BuiltModel built = build_scene_model_reported(s);
    impl_->simulation =
        std::make_unique<rockdd::Simulation>(s, std::move(built.model), std::move(built.mesh_slot));
  });
}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

RunOutcome Simulation::run(const RunSettings& settings, const StepCallback& on_step) {
  return translate_errors([&] {
    // The engine's run carries its counters and state forward: a second run would not be a
    // fresh one.
    if (impl_->ran) throw Error(ErrorKind::error, "a rockdd::api::Simulation runs once");
    impl_->ran = true;
    RunOptions options = run_options(settings);
    if (on_step)
      options.keep_going = [&](const StepReport& r, const Model&) {
        return on_step(Step{r.step, r.time, r.dt, r.end_time});
      };
    const RunResult result = impl_->simulation->run(options);
    return RunOutcome{result.ok, result.reason, result.summary.dump(2)};
  });
}

std::int32_t Simulation::num_nodes() const {
  return impl_->simulation->model().num_nodes();
}

std::int32_t Simulation::num_elements() const {
  return impl_->simulation->model().num_elements();
}

std::span<const double> Simulation::positions() const {
  return impl_->simulation->model().X;
}

std::span<const double> Simulation::displacements() const {
  return impl_->simulation->model().u;
}

std::span<const double> Simulation::stresses() const {
  return impl_->simulation->model().stress;
}

std::span<const double> Simulation::damage() const {
  return impl_->simulation->model().damage;
}

std::span<const std::int32_t> Simulation::element_blocks() const {
  return impl_->simulation->model().element_block;
}

std::span<const std::int32_t> Simulation::connectivity() const {
  return impl_->simulation->model().conn;
}

}  // namespace rockdd::api

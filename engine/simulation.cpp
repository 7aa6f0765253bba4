#include "engine/simulation.hpp"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/internal_force.hpp"
#include "engine/errors.hpp"
#include "engine/loading/external_loads.hpp"
#include "engine/output/probes.hpp"
#include "engine/time/integrator.hpp"

namespace rockdd {
namespace {

/// Run length: `end`, or `steps` x dt, or one step of 1 s in a static scene without [time].
double end_time_of(const Scene& scene) {
  if (scene.time.end) return *scene.time.end;
  return static_cast<double>(scene.time.steps.value_or(1)) * scene.time.dt;
}

const char* analysis_name(Analysis a) {
  switch (a) {
    case Analysis::static_:
      return "static";
    case Analysis::quasi_static:
      return "quasi-static";
    case Analysis::dynamic:
      return "dynamic";
  }
  return "";
}

}  // namespace

Simulation::Simulation(Scene scene, Model model)
    : scene_(std::move(scene)), model_(std::move(model)) {
  bc_ = build_boundary_conditions(scene_, model_);
  if (scene_.analysis == Analysis::static_) check_static_restraint(scene_, model_, bc_);
  reference_loads_ = build_reference_loads(scene_, model_);
  probes_ = std::make_unique<Probes>(scene_, model_);

  coloring_ = color_elements(model_.conn, model_.num_nodes());
  layout_ = build_stiffness_layout(model_.conn, model_.num_nodes(), bc_.equation);
  values_.assign(static_cast<std::size_t>(layout_.pattern.nnz()), 0.0);
  if (bc_.num_equations > 0) solver_.analyze(layout_.pattern);

  const std::size_t num_dofs = model_.X.size();
  for (auto* field :
       {&acceleration_, &f_int_, &f_ext_, &f_ext_old_, &reaction_, &reaction_old_, &u_trial_, &du_})
    field->assign(num_dofs, 0.0);
  rhs_.assign(static_cast<std::size_t>(bc_.num_equations), 0.0);
  for (const InitialSpec& init : scene_.initial) {
    // Rigid motion of the body: v = v0 + omega x (x - centroid).
    const auto& bodies = model_.sets.bodies;
    const auto body = std::find(bodies.begin(), bodies.end(), init.body) - bodies.begin();
    double cx = 0, cy = 0, m = 0;
    std::vector<std::uint8_t> in(static_cast<std::size_t>(model_.num_nodes()), 0);
    for (std::int32_t e = 0; e < model_.num_elements(); ++e)
      if (model_.element_body[e] == body)
        for (int k = 0; k < 3; ++k) in[model_.conn[3 * e + k]] = 1;
    for (std::int32_t n = 0; n < model_.num_nodes(); ++n)
      if (in[n]) {
        cx += model_.node_mass[n] * model_.X[2 * n];
        cy += model_.node_mass[n] * model_.X[2 * n + 1];
        m += model_.node_mass[n];
      }
    if (m <= 0)
      throw InputError(scene_.file.string(), "initial.body", "no body named '" + init.body + "'");
    cx /= m;
    cy /= m;
    for (std::int32_t n = 0; n < model_.num_nodes(); ++n)
      if (in[n]) {
        model_.v[2 * n] = init.velocity[0] - init.angular_velocity * (model_.X[2 * n + 1] - cy);
        model_.v[2 * n + 1] = init.velocity[1] + init.angular_velocity * (model_.X[2 * n] - cx);
      }
  }
}

Simulation::~Simulation() = default;

void Simulation::prepare_system(double mass_coefficient) {
  if (mass_coefficient == factorized_mass_coefficient_ || bc_.num_equations == 0) return;
  {
    ScopedTimer timer(timers_.assembly);
    assemble_stiffness(model_, coloring_, layout_, bc_.equation, mass_coefficient, values_);
  }
  ScopedTimer timer(timers_.factorization);
  solver_.factorize(values_.data());
  factorized_mass_coefficient_ = mass_coefficient;
}

bool Simulation::attempt_step(long step, double dt, double load_factor, StepControl& control) {
  const InertiaTerms inertia = inertia_terms(scene_.analysis, scene_.time.integrator, dt);
  prepare_system(inertia.mass_coefficient);

  const std::size_t num_dofs = model_.X.size();
  for (std::size_t d = 0; d < num_dofs; ++d) {
    du_[d] = bc_.prescribed[d] ? bc_.velocity[d] * dt : 0.0;
    u_trial_[d] = model_.u[d] + du_[d];
    f_ext_[d] = load_factor * reference_loads_[d];
  }
  {
    ScopedTimer timer(timers_.assembly);
    compute_internal_force(model_, coloring_, u_trial_, model_.strain, model_.stress, f_int_);
  }
  for (std::size_t d = 0; d < num_dofs; ++d) {
    const std::int32_t eq = bc_.equation[d];
    if (eq < 0) continue;
    const double m = model_.node_mass[d / 2];
    rhs_[eq] = f_ext_[d] - f_int_[d] +
               m * (inertia.velocity_coefficient * model_.v[d] +
                    inertia.acceleration_coefficient * acceleration_[d]);
  }
  if (bc_.num_equations > 0) {
    ScopedTimer timer(timers_.solve);
    solver_.solve(rhs_.data(), rhs_.data());
  }
  double largest = 0.0;
  for (std::size_t d = 0; d < num_dofs; ++d) {
    if (bc_.equation[d] >= 0) du_[d] = rhs_[bc_.equation[d]];
    if (!std::isfinite(du_[d])) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "step %ld: the displacement increment of node %zu is not finite "
                    "(check stiffness contrasts, restraints and dt)",
                    step, d / 2);
      throw RunFailure(buf);
    }
    largest = std::max(largest, std::abs(du_[d]));
  }
  if (!control.displacement_ok(largest)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "largest displacement increment %.3g m exceeds max_step_displacement", largest);
    control.reject(step, buf);
    return false;
  }
  return true;
}

void Simulation::commit_step(double dt) {
  const std::size_t num_dofs = model_.X.size();
  for (std::size_t d = 0; d < num_dofs; ++d) model_.u[d] += du_[d];
  update_velocity(scene_.analysis, scene_.time.integrator, dt, du_, bc_.prescribed, bc_.velocity,
                  model_.v, acceleration_);
  {
    ScopedTimer timer(timers_.assembly);
    compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, f_int_);
  }
  // The constraints' force on the body, and the work of all external forces (trapezoidal).
  double work = 0.0;
  for (std::size_t d = 0; d < num_dofs; ++d) {
    reaction_[d] = bc_.prescribed[d] ? f_int_[d] - f_ext_[d] : 0.0;
    work += 0.5 * (f_ext_old_[d] + reaction_old_[d] + f_ext_[d] + reaction_[d]) * du_[d];
  }
  external_work_ += work;
  std::swap(f_ext_old_, f_ext_);
  std::swap(reaction_old_, reaction_);
}

EnergyBalance Simulation::energy() const {
  EnergyBalance e;
  for (std::int32_t n = 0; n < model_.num_nodes(); ++n)
    e.kinetic += 0.5 * model_.node_mass[n] *
                 (model_.v[2 * n] * model_.v[2 * n] + model_.v[2 * n + 1] * model_.v[2 * n + 1]);
  e.strain = strain_energy(model_, model_.strain, model_.stress);
  e.external_work = external_work_;
  return e;
}

void Simulation::evaluate_probes(std::vector<double>& row) {
  row.clear();
  // After commit_step the newest reaction sits in reaction_old_.
  probes_->evaluate(model_, reaction_old_, row);
}

RunResult Simulation::run(const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));

  const double end_time = end_time_of(scene_);
  StepControl control(scene_.time);
  std::unique_ptr<RunOutputs> outputs;
  if (options.write_outputs)
    outputs = std::make_unique<RunOutputs>(
        scene_, options.out_root.empty() ? scene_.output.dir : options.out_root, probes_->columns(),
        probes_->has_line_probes());

  // Step 0: the initial state.
  const double initial_factor = load_factor(scene_.analysis, 0.0, end_time);
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    f_ext_old_[d] = initial_factor * reference_loads_[d];
  compute_internal_force(model_, coloring_, model_.u, model_.strain, model_.stress, f_int_);
  // Newmark needs the acceleration that balances the initial state, a0 = M^-1 (F - f_int);
  // starting from a0 = 0 would leave a velocity error of g dt / 2 for the whole run.
  for (std::size_t d = 0; d < model_.X.size(); ++d)
    acceleration_[d] = bc_.prescribed[d] || scene_.analysis != Analysis::dynamic
                           ? 0.0
                           : (f_ext_old_[d] - f_int_[d]) / model_.node_mass[d / 2];
  std::vector<double> row;
  auto record = [&](long step, double time, double dt, bool last) {
    if (!outputs) return;
    ScopedTimer timer(timers_.output);
    evaluate_probes(row);
    outputs->history_row(step, time, dt, row, energy());
    const int every = scene_.output.every;
    if (last || (every > 0 && step % every == 0)) {
      outputs->frame(model_, step, time);
      probes_->write_profiles(model_, outputs->dir() / "profiles", step);
    }
  };
  record(0, 0.0, control.dt(), false);

  RunResult result;
  double t = 0.0;
  const long planned = std::lround(end_time / scene_.time.dt);
  try {
    while (t < end_time * (1.0 - 1e-12)) {
      const long step = steps_ + 1;
      double dt = std::min(control.dt(), end_time - t);
      while (!attempt_step(step, dt, load_factor(scene_.analysis, t + dt, end_time), control)) {
        ++redone_steps_;
        dt = std::min(control.dt(), end_time - t);
      }
      commit_step(dt);
      t += dt;
      steps_ = step;
      control.accept(true);
      const bool last = t >= end_time * (1.0 - 1e-12);
      record(step, t, dt, last);
      if (options.on_step) options.on_step({step, t, dt, end_time, planned}, model_);
    }
  } catch (const RunFailure& failure) {
    result.ok = false;
    result.reason = failure.what();
    if (outputs) {
      ScopedTimer timer(timers_.output);
      outputs->frame(model_, steps_, t);  // the last committed state, for diagnosis
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.summary = summary(result, wall, threads);
  result.summary["dt_changes"] = control.changes();
  if (outputs) {
    for (const auto& [column, peak] : outputs->peaks()) result.summary["peaks"][column] = peak;
    outputs->finish(result.summary);
  }
  return result;
}

nlohmann::json Simulation::summary(const RunResult& result, double wall_seconds,
                                   int threads) const {
  nlohmann::json s;
  s["scene"] = scene_.name;
  s["status"] = result.ok ? "ok" : "failed";
  if (!result.ok) s["reason"] = result.reason;
  s["rockdd_version"] = ROCKDD_VERSION;
  s["threads"] = threads;
  s["wall_seconds"] = wall_seconds;
  s["analysis"] = analysis_name(scene_.analysis);
  s["steps"] = steps_;
  s["redone_steps"] = redone_steps_;
  s["open_close_iterations"] = 0;
  s["max_open_close_per_step"] = 0;
  s["damage_iterations"] = 0;
  s["elements"] = model_.num_elements();
  s["nodes"] = model_.num_nodes();
  s["equations"] = bc_.num_equations;
  s["blocks"] = model_.num_blocks;
  s["damaged_elements"] =
      std::count_if(model_.damage.begin(), model_.damage.end(), [](double w) { return w > 0; });
  s["peaks"] = nlohmann::json::object();
  nlohmann::json defaults = nlohmann::json::object();
  for (const auto& [key, value] : scene_.defaults) defaults[key] = value;
  defaults["mass"] = "lumped";
  s["defaults"] = defaults;
  s["timers"] = {{"assembly", timers_.assembly}, {"factorization", timers_.factorization},
                 {"solve", timers_.solve},       {"contact", timers_.contact},
                 {"damage", timers_.damage},     {"output", timers_.output}};
  const SolverStats& st = solver_.stats();
  s["solver"] = {{"analyses", st.analyses},
                 {"factorizations", st.factorizations},
                 {"updates", st.updates},
                 {"nonzeros", layout_.pattern.nnz()},
                 {"factor_flops", st.last_factor_flops}};
  return s;
}

}  // namespace rockdd

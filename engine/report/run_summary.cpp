#include "engine/report/run_summary.hpp"

#include <algorithm>

#include "engine/common/process_clock.hpp"
#include "engine/contact/contact_stage.hpp"
#include "engine/solver/blas_kernels.hpp"

namespace rockdd {
namespace {

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

void write_counters(const RunStats& c, nlohmann::json& s) {
  s["steps"] = c.steps;
  s["redone_steps"] = c.redone_steps;
  s["redone_by"] = {{"open_close", c.redone_by_open_close},
                    {"displacement", c.redone_by_displacement},
                    {"energy", c.redone_by_energy}};
  s["onset_cuts"] = c.onset_cuts;
  s["located_onsets"] = c.located_onsets;
  s["dt_changes"] = c.dt_changes;
  s["open_close_iterations"] = c.open_close_iterations;
  s["max_open_close_per_step"] = c.max_open_close_per_step;
  s["open_close_relaxed_steps"] = c.open_close_relaxed_steps;
  s["open_close_largest_relaxation"] = c.largest_relaxation;
  s["damage_iterations"] = c.damage_iterations;
  s["damage_iteration_limit_hits"] = c.damage_limit_hits;
  s["damage_stage_passes"] = c.damage_stage_passes;
  s["detached_elements"] = c.detached_elements;
  s["parts_cut_loose"] = c.parts_cut_loose;
  s["restraint_relaxations"] = c.restraint_relaxations;
  s["frame_corrections"] = c.frame_corrections;
}

/// summary.json's "timers": the step stages, the set-up, and with `setup` the whole process.
nlohmann::json timers(const RunReport& report, double wall_seconds,
                      const std::optional<SetupReport>& setup) {
  const StageTimers& stage = report.timers;
  const SetupTimers& set_up = report.setup_timers;
  nlohmann::json t = {
      {"assembly", stage.assembly},    {"factorization", stage.factorization},
      {"solve", stage.solve},          {"contact", stage.contact},
      {"damage", stage.damage},        {"detachment", stage.detachment},
      {"output", stage.output},        {"layout", stage.layout},
      {"analysis", stage.analysis},    {"step_other", std::max(0.0, wall_seconds - stage.sum())},
      {"setup_layout", set_up.layout}, {"setup_analysis", set_up.analysis},
      {"setup", set_up.other}};
  if (!setup) return t;
  double named = setup->scene + setup->meshing + setup->model + set_up.sum() + wall_seconds;
  if (setup->startup) {
    t["startup"] = *setup->startup;
    named += *setup->startup;
  }
  t["scene"] = setup->scene;
  t["meshing"] = setup->meshing;
  t["model"] = setup->model;
  // The process's age when the summary is made; what the named timers miss is the gaps
  // between them (and /proc's 10 ms resolution of the process's start).
  if (const std::optional<double> process = process_age_seconds(); process && setup->startup) {
    t["process"] = *process;
    t["unaccounted"] = *process - named;
  }
  return t;
}

/// The damage keys: the tensile onset of each damageable material (METHOD.md), where damage
/// first appeared, and where a snap-back went on with inertia.
void write_damage(const RunSummaryInputs& in, nlohmann::json& s) {
  const Scene& scene = in.scene;
  nlohmann::json onset = nlohmann::json::object();
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].has_damage())
      onset["material[" + std::to_string(i) + "]"] =
          scene.materials[i].tension_onset == TensionOnset::strain ? "strain" : "stress";
  s["tension_onset"] = onset;
  if (const std::optional<FirstDamage>& first = in.committed.first_damage)
    s["first_damage"] = {
        {"step", first->step}, {"time", first->time}, {"elements", first->elements},
        {"x", first->x},       {"y", first->y},       {"spread", first->spread}};
  else
    s["first_damage"] = nullptr;
  // Moments inside steps (the damage pass after which each first happened), with their frames.
  nlohmann::json events = nlohmann::json::object();
  for (const RunEvent& event : in.committed.events) {
    nlohmann::json& e = events[event.name];
    e = {{"step", event.step},
         {"pass", event.pass},
         {"time", event.time},
         {"damaged_elements", event.damaged_elements},
         {"frame", event.frame.empty() ? nlohmann::json(nullptr) : nlohmann::json(event.frame)}};
    if (event.name == "first_separation") e["part_areas"] = event.parts;
  }
  s["events"] = events;
  if (scene.fracture.snap_back == FractureSpec::SnapBack::dynamic) {
    const std::optional<InertiaSwitch>& to = in.report.inertia_switch;
    s["snap_back_inertia"] =
        to ? nlohmann::json{{"step", to->step}, {"time", to->time}, {"dt", to->dt}}
           : nlohmann::json(nullptr);
  }
}

}  // namespace

nlohmann::json run_summary(const RunSummaryInputs& in) {
  const Scene& scene = in.scene;
  const Model& model = in.model;
  nlohmann::json s;
  s["scene"] = scene.name;
  s["status"] = in.ok ? "ok" : "failed";
  if (!in.ok) s["reason"] = in.reason;
  s["rockdd_version"] = ROCKDD_VERSION;
  s["threads"] = in.threads;
  s["wall_seconds"] = in.wall_seconds;
  s["analysis"] = analysis_name(scene.analysis);  // as the scene gives it
  write_counters(in.report.counters, s);
  s["folded_damage_passes"] = in.system.stats().folded_damage_passes;
  s["untrusted_updated_solves"] = in.system.stats().untrusted_updated_solves;
  s["open_close_shear_swings_settled"] = in.contact ? in.contact->shear_swings_settled() : 0;
  s["open_close_normal_swings_settled"] = in.contact ? in.contact->normal_swings_settled() : 0;
  s["elements"] = model.num_elements();
  s["nodes"] = model.num_nodes();
  s["equations"] = in.equations;
  s["blocks"] = model.num_blocks;
  if (!model.tensile_strength.empty()) write_damage(in, s);
  {
    // The balance of the last committed state, split by where the work went; what is left
    // over measures the scheme's own losses (contact reset, step relinearisation).
    const EnergyBalance& e = in.balance;
    const EnergyAccount& account = in.committed.energy;
    s["energy"] = {{"initial", e.initial},
                   {"external_work", e.external_work},
                   {"kinetic", e.kinetic},
                   {"strain", e.strain},
                   {"damage_dissipation", account.damage},
                   {"friction_dissipation", account.friction},
                   {"snap_back", account.snap_back},
                   {"created_by_resolves", account.created},
                   {"anchor_work", account.anchor},
                   {"integrator_dissipation", account.integrator},
                   {"quasi_static_loss", account.quasi_static},
                   {"unaccounted", e.unaccounted()}};
    // The share every figure is measured against, and what the step control's check saw.
    const double scale = EnergyCheck::scale(e);
    std::string open = energy_balance_warning(e, kEnergyBalanceShare, in.energy_check);
    if (!open.empty() && in.report.disintegration)
      open += "; its last step (" + std::to_string(in.report.disintegration->step) +
              (in.report.disintegration->cause == DisintegrationCause::fragments
                   ? ") broke the specimen into loose fragments"
                   : ") left no chain of rock and closed contacts between its moving and its "
                     "held boundary") +
              ", and quasi-static steps hold what is loose only by the restraint and the mass "
              "term (summary.json disintegration)";
    s["energy_check"] = {{"scale", scale},
                         {"tolerance", in.energy_check.tolerance()},
                         {"created", in.energy_check.total_created()},
                         {"largest_step_created_share", in.energy_check.largest_share()},
                         {"redone_steps", in.energy_check.rejected()},
                         {"unresolved_steps", in.energy_check.unresolved()},
                         {"balance_closes", open.empty()}};
    if (!open.empty()) s["energy_check"]["warning"] = open;
  }
  s["damaged_elements"] =
      std::count_if(model.damage.begin(), model.damage.end(), [](double w) { return w > 0; });
  s["peaks"] = nlohmann::json::object();
  nlohmann::json defaults = nlohmann::json::object();
  for (const auto& [key, value] : scene.defaults) defaults[key] = value;
  defaults["mass"] = "lumped";
  if (in.contact) {
    const ContactParameters& p = in.contact->parameters();
    defaults["contact.normal_stiffness"] = p.normal_stiffness;
    defaults["contact.shear_stiffness"] = p.shear_stiffness;
    defaults["contact.reach"] = p.reach;
    if (!scene.time.max_step_displacement) defaults["time.max_step_displacement"] = p.reach;
  }
  s["defaults"] = defaults;
  s["timers"] = timers(in.report, in.wall_seconds, in.setup);
  if (in.setup) s["mesh_cache"] = mesh_cache_outcome_name(in.setup->mesh_cache);
  const SolverStats& st = in.system.solver_stats();
  s["solver"] = {{"analyses", st.analyses},
                 {"analysis_seconds", st.analysis_seconds},
                 {"factorizations", st.factorizations},
                 {"updates", st.updates},
                 {"updated_columns", st.updated_columns},
                 {"nonzeros", in.system.layout().pattern.nnz()},
                 {"ordering", std::string(fill_ordering_name(st.ordering))},
                 {"ordering_cache", mesh_cache_outcome_name(in.system.ordering_cache())},
                 {"factor_nonzeros", st.factor_nonzeros},
                 {"factor_flops", st.last_factor_flops},
                 {"blas_kernels", blas_kernel_set()}};
  if (scene.time.stop_at_softening) {
    const SofteningMonitor& m = in.report.softening;
    s["softening"] = {{"probe", scene.time.softening_probe},
                      {"fraction", *scene.time.stop_at_softening},
                      {"peak", m.peak},
                      {"peak_step", m.peak_step},
                      {"peak_time", m.peak_time},
                      {"reached", m.reached},
                      {"step", m.step},
                      {"time", m.time},
                      {"value", m.value}};
  }
  if (const std::optional<Disintegration>& d = in.report.disintegration)
    s["disintegration"] = {{"step", d->step},
                           {"time", d->time},
                           {"blocks", d->spread.blocks},
                           {"largest_block_share", d->spread.largest_share},
                           {"fragment_share", kFragmentShare},
                           {"cause", disintegration_cause_name(d->cause)}};
  if (in.report.stopped_by_caller) s["stopped_by_caller"] = true;
  return s;
}

}  // namespace rockdd

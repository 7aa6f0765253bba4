// rockdd.h over the C++ API: every entry catches everything, so no exception reaches C.
#include "rockdd/rockdd.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rockdd/rockdd.hpp"

struct rockdd_scene {
  rockdd::api::Scene scene;
};

struct rockdd_run {
  rockdd::api::Simulation simulation;
  std::optional<std::string> summary;  // the last run's summary.json
};

struct rockdd_ensemble {
  rockdd::api::EnsembleTable table;
};

namespace {

thread_local std::string last_error;

rockdd_status status_of(rockdd::api::ErrorKind kind) {
  switch (kind) {
    case rockdd::api::ErrorKind::bad_input:
      return ROCKDD_BAD_INPUT;
    case rockdd::api::ErrorKind::run_failed:
      return ROCKDD_RUN_FAILED;
    case rockdd::api::ErrorKind::error:
      break;
  }
  return ROCKDD_ERROR;
}

/// Runs `f` (which returns a status) with this thread's message set from what it threw.
template <class F>
rockdd_status guarded(F&& f) noexcept {
  last_error.clear();
  try {
    return f();
  } catch (const rockdd::api::Error& e) {
    last_error = e.what();
    return status_of(e.kind());
  } catch (const std::exception& e) {
    last_error = e.what();
  } catch (...) {
    last_error = "unknown error";
  }
  return ROCKDD_ERROR;
}

rockdd_status bad_argument(const char* what) {
  last_error = what;
  return ROCKDD_BAD_INPUT;
}

std::vector<std::string> override_list(const char* const* overrides, size_t count) {
  std::vector<std::string> list;
  for (size_t i = 0; i < count; ++i) list.emplace_back(overrides[i]);
  return list;
}

}  // namespace

extern "C" {

const char* rockdd_last_error(void) {
  return last_error.c_str();
}

const char* rockdd_version(void) {
  return rockdd::api::version();
}

rockdd_status rockdd_scene_load_file(const char* path, const char* const* overrides,
                                     size_t num_overrides, rockdd_scene** out) {
  return guarded([&] {
    if (!path || !out || (num_overrides > 0 && !overrides))
      return bad_argument("rockdd_scene_load_file: path, out and overrides must not be NULL");
    *out = new rockdd_scene{
        rockdd::api::Scene::from_file(path, override_list(overrides, num_overrides))};
    return ROCKDD_OK;
  });
}

rockdd_status rockdd_scene_load_string(const char* toml, const char* name,
                                       const char* const* overrides, size_t num_overrides,
                                       rockdd_scene** out) {
  return guarded([&] {
    if (!toml || !out || (num_overrides > 0 && !overrides))
      return bad_argument("rockdd_scene_load_string: toml, out and overrides must not be NULL");
    *out = new rockdd_scene{rockdd::api::Scene::from_string(
        toml, override_list(overrides, num_overrides), name ? name : "scene.toml")};
    return ROCKDD_OK;
  });
}

void rockdd_scene_free(rockdd_scene* scene) {
  delete scene;
}

rockdd_status rockdd_run_create(const rockdd_scene* scene, rockdd_run** out) {
  return guarded([&] {
    if (!scene || !out) return bad_argument("rockdd_run_create: scene and out must not be NULL");
    *out = new rockdd_run{rockdd::api::Simulation(scene->scene), std::nullopt};
    return ROCKDD_OK;
  });
}

rockdd_status rockdd_run_execute(rockdd_run* run, const char* out_dir, int threads,
                                 rockdd_step_callback on_step, void* user) {
  return guarded([&] {
    if (!run) return bad_argument("rockdd_run_execute: run must not be NULL");
    rockdd::api::RunSettings settings;
    if (out_dir) settings.out_dir = out_dir;
    settings.threads = threads;
    rockdd::api::StepCallback callback;
    if (on_step)
      callback = [&](const rockdd::api::Step& s) { return on_step(s.step, s.time, user) == 0; };
    rockdd::api::RunOutcome outcome = run->simulation.run(settings, callback);
    run->summary = std::move(outcome.summary_json);
    if (outcome.ok) return ROCKDD_OK;
    last_error = outcome.reason;
    return ROCKDD_RUN_FAILED;
  });
}

void rockdd_run_free(rockdd_run* run) {
  delete run;
}

long rockdd_run_num_nodes(const rockdd_run* run) {
  return run ? run->simulation.num_nodes() : 0;
}

long rockdd_run_num_elements(const rockdd_run* run) {
  return run ? run->simulation.num_elements() : 0;
}

const double* rockdd_run_positions(const rockdd_run* run) {
  return run ? run->simulation.positions().data() : nullptr;
}

const double* rockdd_run_displacements(const rockdd_run* run) {
  return run ? run->simulation.displacements().data() : nullptr;
}

const double* rockdd_run_stresses(const rockdd_run* run) {
  return run ? run->simulation.stresses().data() : nullptr;
}

const double* rockdd_run_damage(const rockdd_run* run) {
  return run ? run->simulation.damage().data() : nullptr;
}

const int32_t* rockdd_run_blocks(const rockdd_run* run) {
  return run ? run->simulation.element_blocks().data() : nullptr;
}

const int32_t* rockdd_run_connectivity(const rockdd_run* run) {
  return run ? run->simulation.connectivity().data() : nullptr;
}

const char* rockdd_run_summary_json(const rockdd_run* run) {
  return run && run->summary ? run->summary->c_str() : nullptr;
}

rockdd_status rockdd_ensemble_run(const rockdd_scene* scene, long realizations,
                                  const uint64_t* first_seed, const char* out_dir, int threads,
                                  rockdd_ensemble** out) {
  return guarded([&] {
    if (!scene || !out)
      return bad_argument("rockdd_ensemble_run: scene and out must not be NULL");
    if (realizations < 1)
      return bad_argument(("rockdd_ensemble_run: realizations: expected an integer >= 1, got " +
                           std::to_string(realizations))
                              .c_str());
    rockdd::api::RunSettings settings;
    if (out_dir) settings.out_dir = out_dir;
    settings.threads = threads;
    std::optional<std::uint64_t> first;
    if (first_seed) first = *first_seed;
    *out = new rockdd_ensemble{
        rockdd::api::run_ensemble(scene->scene, realizations, first, settings)};
    return ROCKDD_OK;
  });
}

void rockdd_ensemble_free(rockdd_ensemble* ensemble) {
  delete ensemble;
}

size_t rockdd_ensemble_num_columns(const rockdd_ensemble* ensemble) {
  return ensemble ? ensemble->table.columns.size() : 0;
}

const char* rockdd_ensemble_column(const rockdd_ensemble* ensemble, size_t column) {
  return ensemble && column < ensemble->table.columns.size()
             ? ensemble->table.columns[column].c_str()
             : nullptr;
}

long rockdd_ensemble_column_index(const rockdd_ensemble* ensemble, const char* name) {
  if (!ensemble || !name) return -1;
  const auto& columns = ensemble->table.columns;
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return static_cast<long>(i);
  return -1;
}

size_t rockdd_ensemble_num_rows(const rockdd_ensemble* ensemble) {
  return ensemble ? ensemble->table.rows.size() : 0;
}

uint64_t rockdd_ensemble_seed(const rockdd_ensemble* ensemble, size_t row) {
  return ensemble && row < ensemble->table.rows.size() ? ensemble->table.rows[row].seed : 0;
}

const char* rockdd_ensemble_status(const rockdd_ensemble* ensemble, size_t row) {
  return ensemble && row < ensemble->table.rows.size()
             ? ensemble->table.rows[row].status.c_str()
             : nullptr;
}

const char* rockdd_ensemble_reason(const rockdd_ensemble* ensemble, size_t row) {
  return ensemble && row < ensemble->table.rows.size()
             ? ensemble->table.rows[row].reason.c_str()
             : nullptr;
}

const char* rockdd_ensemble_cell(const rockdd_ensemble* ensemble, size_t row, size_t column) {
  if (!ensemble || row >= ensemble->table.rows.size()) return nullptr;
  const auto& cells = ensemble->table.rows[row].cells;
  return column < cells.size() ? cells[column].c_str() : nullptr;
}

double rockdd_ensemble_value(const rockdd_ensemble* ensemble, size_t row, size_t column) {
  const char* cell = rockdd_ensemble_cell(ensemble, row, column);
  if (!cell || *cell == '\0') return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double value = std::strtod(cell, &end);
  return *end == '\0' ? value : std::numeric_limits<double>::quiet_NaN();
}

}  // extern "C"

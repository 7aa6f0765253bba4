#ifndef ROCKDD_H
#define ROCKDD_H
/* rockdd's C API: opaque handles over the C++ engine. No function lets an exception out: each
 * returns a status, and rockdd_last_error() says why (per thread). Arrays point into the
 * engine's own storage, valid until the next rockdd_run_execute or rockdd_run_free. */
#include <stddef.h>
#include <stdint.h>

#include "rockdd/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A read and validated scene. */
typedef struct rockdd_scene rockdd_scene;
/* A simulation of a scene: its model, its run and what the run left. */
typedef struct rockdd_run rockdd_run;
/* An ensemble's table: one row per seed, as rockdd mc's mc.csv. */
typedef struct rockdd_ensemble rockdd_ensemble;

/* Outcome of a call; the values are the command line's exit statuses where it has them. */
typedef enum rockdd_status {
  ROCKDD_OK = 0,
  ROCKDD_RUN_FAILED = 1, /* a numerical failure: the run ended early (its summary says why) */
  ROCKDD_BAD_INPUT = 2,  /* a bad scene key, file or argument */
  ROCKDD_ERROR = 3       /* anything else (out of memory, an I/O error) */
} rockdd_status;

/* Called after each committed step; nonzero stops the run there (it ends ROCKDD_OK). */
typedef int (*rockdd_step_callback)(long step, double time, void* user);

/* The message of this thread's last failed call ("" when none); valid until its next call. */
ROCKDD_API const char* rockdd_last_error(void);
/* The rockdd version string. */
ROCKDD_API const char* rockdd_version(void);

/* Reads the scene file `path` after `num_overrides` "key.path=value" overrides (may be NULL
 * when 0). On success *out is a new scene for rockdd_scene_free. */
ROCKDD_API rockdd_status rockdd_scene_load_file(const char* path, const char* const* overrides,
                                                size_t num_overrides, rockdd_scene** out);
/* As rockdd_scene_load_file from TOML text; `name` stands for the file in messages and
 * anchors relative paths (NULL: "scene.toml"). */
ROCKDD_API rockdd_status rockdd_scene_load_string(const char* toml, const char* name,
                                                  const char* const* overrides,
                                                  size_t num_overrides, rockdd_scene** out);
/* Frees a scene (NULL is fine). */
ROCKDD_API void rockdd_scene_free(rockdd_scene* scene);

/* Meshes `scene` and builds its model; *out is a new run for rockdd_run_free. */
ROCKDD_API rockdd_status rockdd_run_create(const rockdd_scene* scene, rockdd_run** out);
/* Runs to the end or until `on_step` (may be NULL) returns nonzero. `out_dir` NULL: no files.
 * `threads` 0: every hardware thread. ROCKDD_RUN_FAILED when the run failed numerically. */
ROCKDD_API rockdd_status rockdd_run_execute(rockdd_run* run, const char* out_dir, int threads,
                                            rockdd_step_callback on_step, void* user);
/* Frees a run (NULL is fine). */
ROCKDD_API void rockdd_run_free(rockdd_run* run);

/* Counts of the current model (fracture adds nodes during a run). */
ROCKDD_API long rockdd_run_num_nodes(const rockdd_run* run);
ROCKDD_API long rockdd_run_num_elements(const rockdd_run* run);
/* Reference positions and displacements: 2 per node (x, y). */
ROCKDD_API const double* rockdd_run_positions(const rockdd_run* run);
ROCKDD_API const double* rockdd_run_displacements(const rockdd_run* run);
/* Element stresses: 3 per element (sxx, syy, sxy; Pa). */
ROCKDD_API const double* rockdd_run_stresses(const rockdd_run* run);
/* Element damage, 1 per element. */
ROCKDD_API const double* rockdd_run_damage(const rockdd_run* run);
/* Element block ids, 1 per element. */
ROCKDD_API const int32_t* rockdd_run_blocks(const rockdd_run* run);
/* Element connectivity: 3 node ids per element (counter-clockwise), 0-based indices into the
 * nodes of rockdd_run_positions and rockdd_run_displacements: with them a caller rebuilds the
 * mesh (fracture splits nodes, so take all three again after a run). */
ROCKDD_API const int32_t* rockdd_run_connectivity(const rockdd_run* run);
/* The last run's summary.json content; NULL before a run. */
ROCKDD_API const char* rockdd_run_summary_json(const rockdd_run* run);

/* Runs `realizations` seeds of `scene` one after the other in this process, from *first_seed
 * (NULL: the scene's seed), as rockdd mc's workers run them. With `out_dir` (may be NULL) each
 * leaves its files in out_dir/seed_<seed>; the peaks.* columns come from those outputs and are
 * empty without. `threads` 0: every hardware thread. A realization that fails numerically is
 * a row with status "failed", not a failed call. ROCKDD_BAD_INPUT when the scene has no
 * heterogeneous material or `realizations` < 1. On success *out is a new table for
 * rockdd_ensemble_free. */
ROCKDD_API rockdd_status rockdd_ensemble_run(const rockdd_scene* scene, long realizations,
                                             const uint64_t* first_seed, const char* out_dir,
                                             int threads, rockdd_ensemble** out);
/* Frees an ensemble's table (NULL is fine). */
ROCKDD_API void rockdd_ensemble_free(rockdd_ensemble* ensemble);
/* The value columns, in mc.csv's order (between its `status` and `reason`): steps,
 * wall_seconds, peaks.<probe>.<field>, ... (docs/scene.md, "Ensembles"). */
ROCKDD_API size_t rockdd_ensemble_num_columns(const rockdd_ensemble* ensemble);
/* The name of value column `column`; NULL when out of range. */
ROCKDD_API const char* rockdd_ensemble_column(const rockdd_ensemble* ensemble, size_t column);
/* The index of the value column `name`; -1 when there is none. */
ROCKDD_API long rockdd_ensemble_column_index(const rockdd_ensemble* ensemble, const char* name);
/* One row per seed, in seed order. */
ROCKDD_API size_t rockdd_ensemble_num_rows(const rockdd_ensemble* ensemble);
/* Row `row`'s seed (0 when out of range). */
ROCKDD_API uint64_t rockdd_ensemble_seed(const rockdd_ensemble* ensemble, size_t row);
/* Row `row`'s status, "ok" or "failed", and why it failed ("" when ok); NULL out of range. */
ROCKDD_API const char* rockdd_ensemble_status(const rockdd_ensemble* ensemble, size_t row);
ROCKDD_API const char* rockdd_ensemble_reason(const rockdd_ensemble* ensemble, size_t row);
/* A cell as mc.csv writes it ("" when empty); NULL when out of range. */
ROCKDD_API const char* rockdd_ensemble_cell(const rockdd_ensemble* ensemble, size_t row,
                                            size_t column);
/* A cell as a number; NaN when it is empty or out of range. */
ROCKDD_API double rockdd_ensemble_value(const rockdd_ensemble* ensemble, size_t row,
                                        size_t column);

#ifdef __cplusplus
}
#endif
#endif

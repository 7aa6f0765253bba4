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
/* The last run's summary.json content; NULL before a run. */
ROCKDD_API const char* rockdd_run_summary_json(const rockdd_run* run);

#ifdef __cplusplus
}
#endif
#endif

/* Runs a cantilever scene through rockdd's C API and prints the tip's vertical displacement.
 *   tip_c data/cantilever_model_1.toml */
#include <rockdd/rockdd.h>

#include <stdio.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: tip_c SCENE\n");
    return 2;
  }
  rockdd_scene* scene = NULL;
  rockdd_run* run = NULL;
  rockdd_status status = rockdd_scene_load_file(argv[1], NULL, 0, &scene);
  if (status == ROCKDD_OK) status = rockdd_run_create(scene, &run);
  if (status == ROCKDD_OK) status = rockdd_run_execute(run, NULL, 1, NULL, NULL);
  if (status != ROCKDD_OK) {
    fprintf(stderr, "rockdd: %s\n", rockdd_last_error());
    rockdd_run_free(run);
    rockdd_scene_free(scene);
    return (int)status;
  }
  /* The tip: the node nearest the middle of the free end (0.04, 0.005). */
  const double* X = rockdd_run_positions(run);
  const double* u = rockdd_run_displacements(run);
  long tip = 0;
  double nearest = 1e300;
  for (long n = 0; n < rockdd_run_num_nodes(run); ++n) {
    const double dx = X[2 * n] - 0.04, dy = X[2 * n + 1] - 0.005;
    if (dx * dx + dy * dy < nearest) {
      nearest = dx * dx + dy * dy;
      tip = n;
    }
  }
  printf("tip uy = %.17g\n", u[2 * tip + 1]);
  rockdd_run_free(run);
  rockdd_scene_free(scene);
  return 0;
}

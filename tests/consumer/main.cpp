// Runs a cantilever scene through rockdd's C++ API and prints the tip's vertical displacement.
//   tip_cpp data/cantilever_model_1.toml
#include <rockdd/rockdd.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: tip_cpp SCENE\n");
    return 2;
  }
  try {
    const rockdd::api::Scene scene = rockdd::api::Scene::from_file(argv[1]);
    rockdd::api::Simulation sim(scene);
    rockdd::api::RunSettings settings;  // no out_dir: no files, the summary comes anyway
    settings.threads = 1;
    const rockdd::api::RunOutcome outcome = sim.run(settings);
    if (!outcome.ok) {
      std::fprintf(stderr, "run failed: %s\n", outcome.reason.c_str());
      return 1;
    }
    // The tip: the node nearest the middle of the free end (0.04, 0.005).
    const auto X = sim.positions();
    const auto u = sim.displacements();
    std::size_t tip = 0;
    double nearest = 1e300;
    for (std::size_t n = 0; n < X.size() / 2; ++n) {
      const double dx = X[2 * n] - 0.04, dy = X[2 * n + 1] - 0.005;
      if (dx * dx + dy * dy < nearest) {
        nearest = dx * dx + dy * dy;
        tip = n;
      }
    }
    std::printf("tip uy = %.17g\n", u[2 * tip + 1]);
    return 0;
  } catch (const rockdd::api::Error& e) {
    std::fprintf(stderr, "rockdd: %s\n", e.what());
    return 2;
  }
}

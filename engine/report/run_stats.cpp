#include "engine/report/run_stats.hpp"

namespace rockdd {

void RunStats::write(nlohmann::json& s) const {
  s["steps"] = steps;
  s["redone_steps"] = redone_steps;
  s["open_close_iterations"] = open_close_iterations;
  s["max_open_close_per_step"] = max_open_close_per_step;
  s["open_close_relaxed_steps"] = open_close_relaxed_steps;
  s["open_close_largest_relaxation"] = largest_relaxation;
  s["damage_iterations"] = damage_iterations;
  s["damage_iteration_limit_hits"] = damage_limit_hits;
  s["detached_elements"] = detached_elements;
  s["parts_cut_loose"] = parts_cut_loose;
}

}  // namespace rockdd

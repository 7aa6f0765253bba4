#pragma once
// What Simulation::run returns: whether the run ended ok, why not, and its summary.json.
#include <string>

#include <nlohmann/json.hpp>

namespace rockdd {

/// Outcome of a run: "ok", or "failed" with the reason; the summary.json content.
struct RunResult {
  bool ok = true;
  std::string reason;
  nlohmann::json summary;
};

}  // namespace rockdd

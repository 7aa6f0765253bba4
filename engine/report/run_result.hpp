#pragma once
// What Simulation::run returns: whether the run ended ok, why not, and its summary.json.
#include <string>

#include <nlohmann/json.hpp>

namespace rockdd {

// The implicit destructor runs nlohmann::json's, which frees nested values through a vector it
// may grow: out of memory there ends the process, which is what clang-tidy warns of.
/// Outcome of a run: "ok", or "failed" with the reason; the summary.json content.
// NOLINTNEXTLINE(bugprone-exception-escape)
struct RunResult {
  bool ok = true;
  std::string reason;
  nlohmann::json summary;
};

}  // namespace rockdd

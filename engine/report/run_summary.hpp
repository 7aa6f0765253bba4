#pragma once
// summary.json: what one run did, from the report, the state it ended in and the solver's
// counters. The one place that writes the run's JSON (docs/scene.md lists every key).
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/model/model.hpp"
#include "engine/output/run_outputs.hpp"
#include "engine/report/run_report.hpp"
#include "engine/report/setup_report.hpp"
#include "engine/scene/scene.hpp"
#include "engine/solver/cholmod_solver.hpp"
#include "engine/solver/linear_system.hpp"
#include "engine/state/committed_state.hpp"
#include "engine/time/energy_check.hpp"

namespace rockdd {

class ContactStage;

/// Everything summary.json reports, as the step loop hands it over at the end of a run.
struct RunSummaryInputs {
  const Scene& scene;
  const Model& model;
  const RunReport& report;
  const CommittedState& committed;  // the energy account and the first damage
  EnergyBalance balance;            // of the committed state
  const ContactStage* contact;      // null in a scene without contacts
  const LinearSystem& system;
  std::int32_t equations = 0;
  bool ok = true;
  std::string reason;  // why a failed run failed
  double wall_seconds = 0.0;
  int threads = 0;
  const std::optional<SetupReport>& setup;  // what came before the Simulation, when measured
  const EnergyCheck& energy_check;          // what the steps created, and what it rejected
};

/// The summary.json of a run (peaks and outputs' own keys are added by RunOutputs).
nlohmann::json run_summary(const RunSummaryInputs& in);

}  // namespace rockdd

// The section 7 study (`hexcal simulate`; docs/calibration.md): the
// parameter error of pose sets over repeated simulated calibrations (Fig. 14),
// optionally against the number of poses (Fig. 15), with its table and figures.
//
//   SimulateRequest request;
//   request.robot = "inria-left-hand";
//   request.sets = "random,boundary,plan.csv";
//   StatusOr<SimulateOutcome> study = RunSimulationStudy(request, hooks);
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/job_hooks.h"
#include "core/robot.h"
#include "core/simulation.h"
#include "workflow/simulate_options.h"

namespace hexcal::workflow {

struct SimulateOutcome {
  SimulateRequest request;  // as resolved (noise applied)
  Robot robot;
  SimulationResult result;
  std::optional<SweepResult> sweep;
  std::vector<std::string> figures;  // files written under `plots`
  double seconds = 0;
  // Per set, the mean error a fixed set is predicted to give (plan_prediction.h);
  // none for random sets, whose poses change from run to run.
  std::vector<std::optional<double>> predicted_mean;
};

// Stages through hooks: "simulate (runs)", then "sweep (runs)".
StatusOr<SimulateOutcome> RunSimulationStudy(SimulateRequest request, const JobHooks& hooks = {});

nlohmann::json ToJson(const SimulateOutcome& outcome);
std::string FormatSimulateSummary(const SimulateOutcome& outcome);

}  // namespace hexcal::workflow

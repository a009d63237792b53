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

namespace hexcal::workflow {

struct SimulateRequest {
  std::string robot;                    // robot file or preset name
  std::string sets = "random,boundary";  // comma-separated: random, boundary or pose CSV files
  int poses = 18;                       // poses of the random set
  bool poses_given = false;             // `poses` also trims the boundary set
  bool weighted = false;                // calibrate with residuals weighted by the study's noise model
  std::string random_box;               // "x:-5:5,y:-5:5,..." for the random sets
  std::string sweep;                    // "MIN:MAX" poses for Fig. 15; empty: none
  std::string csv;                      // table to write; may be empty
  std::string plots;                    // folder for fig14/fig15 SVG and PNG; may be empty
  bool force = false;                   // replace an existing `csv` table or `plots` figures
  SimulationOptions study;              // runs, seed, perturbation, noise, threads
  std::vector<std::pair<std::string, std::string>> noise_entries;  // over study.noise (NoiseModelOptions)
};

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

// The Plan step (`hexcal plan`, the GUI's Plan panel, the demo): the
// candidate pool and the initial set, IOOPS (core/ioops.h), the D-optimality
// certificate, and the plan and history files.
//
//   PlanRequest request;
//   request.robot = "inria-left-hand";
//   request.planner_entries = {{"poses", "18"}, {"tabu", "4"}};
//   request.out = "plan.csv";
//   StatusOr<PlanOutcome> plan = PlanFromRequest(request, hooks);
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/ioops.h"
#include "core/job_hooks.h"
#include "core/plan_certificate.h"
#include "workflow/plan_options.h"
#include "workflow/plan_prediction.h"

namespace hexcal::workflow {

using OptionEntries = std::vector<std::pair<std::string, std::string>>;

struct CandidatePool {
  std::vector<Vector6d> poses;
  nlohmann::json sources;  // [{"kind": ..., "count": ...}, ...]
};

// From a file, or pooled generated sets (default: one random set). Poses that
// break a measurement constraint are dropped. hooks.cancel stops a generated set.
StatusOr<CandidatePool> BuildCandidatePool(const PlanningModel& model, const std::string& file,
                                           const std::vector<std::string>& kinds, int count, bool continuous,
                                           uint64_t seed, const JobHooks& hooks);

// N starting poses: random | uniform | boundary (N drawn from the boundary set) | a pose CSV.
StatusOr<std::vector<Vector6d>> InitialPoses(const PlanningModel& model, const std::string& init, int count,
                                             uint64_t seed);

Status WritePlanCsv(const std::string& path, const PlanningModel& model, const std::vector<Vector6d>& poses);
Status WriteHistoryCsv(const std::string& path, const PlanResult& plan);

struct PlanOutcome {
  PlanSetup setup;
  CandidatePool pool;
  PlanResult plan;                             // both phases' history; the final plan
  std::optional<PlanCertificate> certificate;  // with setup.certificate, on the pool and the plan's poses
  std::string out;                             // the plan CSV written, if any
  // The finite phase's criterion and iterations, when a continuous phase followed it.
  std::optional<double> finite_primary;
  int finite_iterations = 0;
  NoiseModel noise;           // the prediction's (the model's, else the paper's)
  PlanPrediction prediction;  // for calibrate's default, unweighted
  std::string length_unit{};  // the robot's, for the figures
  // The poses a straight-line controller (LinuxCNC's G0) cannot reach from the
  // centre of the sampling box through moves within the strokes
  // (core/straight_moves.h), as "pose K: why"; empty when it reaches all.
  std::vector<std::string> unreachable{};
  // With a tracker (PlanningModel::tracker): the smallest and largest σ of a
  // reflector's coordinate over the plan's poses (robot unit), and whether
  // its line of sight was a constraint; the prediction used each pose's covariance.
  std::optional<std::pair<double, double>> reflector_sigma{};
  bool line_of_sight = false;
};

// The poses a straight-line controller cannot reach from the centre of the
// sampling box (PlanOutcome::unreachable).
std::vector<std::string> UnreachablePoses(const Robot& robot, const std::vector<Vector6d>& poses);

// The summary `hexcal plan --json` prints.
nlohmann::json ToJson(const PlanOutcome& outcome);
// The lines `hexcal plan` prints.
std::string FormatPlanSummary(const PlanOutcome& outcome);

// Pool, initial set, IOOPS on the pool, then (polish, or `continuous`)
// continuous IOOPS from that plan, the certificates and the prediction, on a
// model and setup already resolved. The S criterion without a noise model
// weights by the paper's noise levels. Stages through hooks: "candidates",
// "planning", "polishing" or "continuous", "certificate", "prediction".
// `on_iteration` sees each history entry as it is recorded, numbered on
// through both phases.
StatusOr<PlanOutcome> RunPlan(const PlanningModel& model, const PlanSetup& setup,
                              const std::string& candidates_file = "", const JobHooks& hooks = {},
                              const PlanIterationObserver& on_iteration = {});

struct PlanRequest {
  std::string robot;            // robot file or preset name; or
  std::string session;          // a session folder: its robot, noise and tracker (session_plan_model.h)
  std::string settings;         // plan settings YAML (noise, planner, camera visibility); may be empty
  std::string candidates_file;  // candidate pose CSV instead of generated sets; may be empty
  // (key, value) over the defaults and the settings file's sections: the flags.
  OptionEntries planner_entries;  // keys of PlanSetupOptions()
  OptionEntries noise_entries;    // keys of NoiseModelOptions(); any makes the plan noise-weighted
  std::string out;                // plan CSV to write; may be empty
  std::string history;            // indices per iteration CSV; may be empty
};

// Loads the robot (or the session's model) and the settings, applies the
// entries (defaults < session < settings file < request), plans and writes
// `out` and `history`.
StatusOr<PlanOutcome> PlanFromRequest(const PlanRequest& request, const JobHooks& hooks = {});

}  // namespace hexcal::workflow

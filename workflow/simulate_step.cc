#include "workflow/simulate_step.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "charts/chart_render.h"
#include "charts/figures.h"
#include "core/atomic_file.h"
#include "core/candidates.h"
#include "core/csv.h"
#include "core/noise_model.h"
#include "core/robot_io.h"
#include "workflow/plan_prediction.h"

namespace hexcal::workflow {
namespace {

// --plots DIR: fig14.svg/.png and, with a sweep, fig15_mean and fig15_std
// (charts/figures.h) in DIR, created if missing.
Status WriteFigures(const std::string& directory, const SimulationResult& result, const SweepResult* sweep,
                    const std::string& length_unit, std::vector<std::string>* written) {
  if (Status s = charts::CreatePlotsFolder(directory); !s.ok()) return s;
  if (Status s = charts::WriteChartFiles(charts::Fig14Chart(result, length_unit), directory, "fig14", written);
      !s.ok()) {
    return s;
  }
  if (sweep == nullptr) return Status::Ok();
  for (bool std_dev : {false, true}) {
    if (Status s = charts::WriteChartFiles(charts::Fig15Chart(*sweep, length_unit, std_dev), directory,
                                           std_dev ? "fig15_std" : "fig15_mean", written);
        !s.ok()) {
      return s;
    }
  }
  return Status::Ok();
}

// "x:-5:5,q3:-20:20" -> a pose box with those bounds.
StatusOr<PoseBox> ParseBox(const std::string& text) {
  static const char* kNames[6] = {"x", "y", "z", "q1", "q2", "q3"};
  PoseBox box;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    const size_t a = item.find(':'), b = item.rfind(':');
    int index = -1;
    for (int k = 0; k < 6 && a != std::string::npos; ++k) {
      if (item.substr(0, a) == kNames[k]) index = k;
    }
    if (index < 0 || a == b)
      return Status::BadOption("random_box", "'" + item + "' is not NAME:MIN:MAX (x, y, z, q1, q2, q3)");
    StatusOr<double> lo = ParseNumber(item.substr(a + 1, b - a - 1)), hi = ParseNumber(item.substr(b + 1));
    if (!lo.ok() || !hi.ok() || !(*lo < *hi))
      return Status::BadOption("random_box", "'" + item + "' needs finite MIN < MAX");
    box.bounds[index] = Range{*lo, *hi};
  }
  return box;
}

StatusOr<std::pair<int, int>> ParseSweep(const std::string& text) {
  const size_t colon = text.find(':');
  if (colon != std::string::npos) {
    StatusOr<double> lo = ParseNumber(text.substr(0, colon)), hi = ParseNumber(text.substr(colon + 1));
    // Bounds checked before the casts: a double beyond int's range cannot be cast.
    if (lo.ok() && hi.ok() && IsSweepRange(*lo, *hi))
      return std::make_pair(static_cast<int>(*lo), static_cast<int>(*hi));
  }
  return Status::BadOption("sweep", "'" + text + "' is not MIN:MAX with " + SweepRangeRule() + ", e.g. 8:41");
}

// "random" draws poses in every run, "boundary" is the boundary candidate set
// (its first --poses poses when --poses is given), anything else a pose file.
StatusOr<std::vector<SimulationPoseSet>> ResolveSets(const Robot& robot, const SimulateRequest& cli, const JobHooks& hooks) {
  std::vector<SimulationPoseSet> sets;
  std::stringstream list(cli.sets);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "random") {
      sets.push_back(RandomPoseSet(cli.poses));
      if (!cli.random_box.empty()) {
        StatusOr<PoseBox> box = ParseBox(cli.random_box);
        if (!box.ok()) return box.status();
        sets.back().box = *box;
      }
    } else if (name == "boundary") {
      CandidateOptions options;
      options.kind = CandidateKind::kBoundary;
      hooks.Stage("boundary poses");
      StatusOr<CandidateSet> boundary =
          GenerateCandidates(robot, options, hooks);
      if (!boundary.ok()) return boundary.status();
      std::vector<Vector6d> poses = std::move(boundary->poses);
      if (cli.poses_given && static_cast<int>(poses.size()) > cli.poses) poses.resize(cli.poses);
      sets.push_back(FixedPoseSet("boundary", std::move(poses)));
    } else if (name.empty()) {
      return Status::BadOption("sets", "empty entry in '" + cli.sets + "'");
    } else {
      StatusOr<std::vector<Vector6d>> poses = LoadPoses(name);
      if (!poses.ok()) return poses.status();
      sets.push_back(FixedPoseSet(name, std::move(*poses)));
    }
  }
  return sets;
}

nlohmann::json OptionalNumber(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json SetJson(const SetError& set, const std::optional<double>& predicted = std::nullopt) {
  return {{"name", set.name},
          {"predicted_mean", OptionalNumber(predicted)},
          {"predicted_ratio", OptionalNumber(predicted ? std::optional<double>(set.mean / *predicted) : std::nullopt)},
          {"poses", set.poses},
          {"mean", set.mean},
          {"std", set.std},
          {"ratio_to_random", OptionalNumber(set.ratio_to_random)},
          {"mean_estimate_error", set.mean_estimate_error},
          {"runs", set.runs},
          {"failed_runs", set.failed_runs}};
}

nlohmann::json ResultJson(const Robot& robot, const SimulateRequest& cli, const SimulationResult& result,
                          const std::optional<SweepResult>& sweep, const std::vector<std::optional<double>>& predicted) {
  nlohmann::json sets = nlohmann::json::array();
  for (size_t k = 0; k < result.sets.size(); ++k) sets.push_back(SetJson(result.sets[k], predicted.at(k)));
  nlohmann::json j = {{"before", {{"mean", result.before.mean}, {"std", result.before.std}}},
                      {"sets", sets},
                      {"robot", robot.name},
                      {"length_unit", LengthUnitName(robot.length_unit)},
                      {"runs", cli.study.runs},
                      {"seed", cli.study.seed},
                      {"perturb", cli.study.perturb},
                      {"weighted", cli.study.calibration.weighted},
                      {"random_box", cli.random_box},
                      {"noise", NoiseModelJson(cli.study.noise)}};
  if (sweep) {
    nlohmann::json points = nlohmann::json::array();
    for (const SweepPoint& point : sweep->points) {
      nlohmann::json point_sets = nlohmann::json::array();
      for (const SetError& set : point.sets) point_sets.push_back(SetJson(set));
      points.push_back({{"poses", point.poses}, {"sets", point_sets}});
    }
    j["sweep"] = points;
  }
  return j;
}

void PrintSetRow(const std::string& name, const std::string& poses, double mean, double std,
                 const std::optional<double>& predicted, const std::optional<double>& ratio, std::ostream& out) {
  char line[200];
  std::snprintf(line, sizeof line, "%-28s %6s %12.4g %12.4g", name.c_str(), poses.c_str(), mean, std);
  out << line;
  if (predicted) {
    std::snprintf(line, sizeof line, " %12.4g", *predicted);
  } else {
    std::snprintf(line, sizeof line, " %12s", "-");
  }
  out << line;
  if (ratio) {
    std::snprintf(line, sizeof line, " %12.3g", *ratio);
    out << line;
    if (*ratio < 1 && *ratio > 0) out << "  (" << std::lround(1 / *ratio) << "x smaller)";
  }
  out << "\n";
}

// Fig. 15 as a table: one row per number of poses, mean (std) per set; "-" where a set is too short.
void PrintSweep(const SimulationResult& result, const SweepResult& sweep, const char* unit, std::ostream& out) {
  out << "\nFig. 15: error against the number of poses, mean (std) in " << unit << "\n";
  char cell[64];
  std::snprintf(cell, sizeof cell, "%6s", "poses");
  out << cell;
  for (const SetError& set : result.sets) {
    std::snprintf(cell, sizeof cell, "  %24s", set.name.c_str());
    out << cell;
  }
  out << "\n";
  for (const SweepPoint& point : sweep.points) {
    std::snprintf(cell, sizeof cell, "%6d", point.poses);
    out << cell;
    for (const SetError& set : result.sets) {
      const auto it =
          std::find_if(point.sets.begin(), point.sets.end(), [&](const SetError& e) { return e.name == set.name; });
      if (it == point.sets.end()) {
        std::snprintf(cell, sizeof cell, "  %24s", "-");
      } else {
        std::snprintf(cell, sizeof cell, "  %11.4g (%10.4g)", it->mean, it->std);
      }
      out << cell;
    }
    out << "\n";
  }
}

void PrintReport(const Robot& robot, const SimulateRequest& cli, const SimulationResult& result,
                 const std::optional<SweepResult>& sweep, const std::vector<std::optional<double>>& predicted,
                 std::ostream& out) {
  const char* unit = LengthUnitName(robot.length_unit);
  const SimulationOptions& study = cli.study;
  out << "section 7 study on robot " << robot.name << ": " << study.runs << " runs, seed " << study.seed << "\n"
      << "true robot: nominal + uniform perturbation within ±" << study.perturb << " " << unit
      << " of each of the 42 parameters\n"
      << "noise (uniform): ±" << study.noise.position << " " << unit << " position, ±" << study.noise.angle_deg
      << " deg angles, ±" << study.noise.leg << " " << unit << " leg readings\n\n"
      << "error |P_est - P_true| over the 42 parameters and all runs (" << unit << ")\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-28s %6s %12s %12s %12s %12s\n", "set", "poses", "mean", "std", "predicted",
                "/ random");
  out << line;
  PrintSetRow("before calibration", "-", result.before.mean, result.before.std, std::nullopt, std::nullopt, out);
  for (size_t k = 0; k < result.sets.size(); ++k) {
    const SetError& set = result.sets[k];
    PrintSetRow(set.name, std::to_string(set.poses), set.mean, set.std, predicted.at(k), set.ratio_to_random, out);
  }
  for (const SetError& set : result.sets) {
    if (set.failed_runs > 0) {
      out << "warning: " << set.name << ": " << set.failed_runs << " of " << study.runs
          << " calibrations failed and are not in the statistics; first: " << set.first_failure << "\n";
    }
  }
  if (sweep) PrintSweep(result, *sweep, unit, out);
}

Status WriteTable(const std::string& path, const SimulationResult& result, const std::optional<SweepResult>& sweep) {
  std::vector<std::vector<std::string>> rows;
  auto add = [&](const std::string& study, const SetError& set) {
    rows.push_back({study, set.name, std::to_string(set.poses), FormatNumber(set.mean), FormatNumber(set.std),
                    set.ratio_to_random ? FormatNumber(*set.ratio_to_random) : ""});
  };
  rows.push_back({"before", "before", "", FormatNumber(result.before.mean), FormatNumber(result.before.std), ""});
  for (const SetError& set : result.sets) add("fig14", set);
  if (sweep) {
    for (const SweepPoint& point : sweep->points) {
      for (const SetError& set : point.sets) add("sweep", set);
    }
  }
  return WriteCsv(path, {"study", "name", "poses", "mean", "std", "ratio_to_random"}, rows);
}

// The mean error each fixed set is predicted to give under the study's noise
// and calibration (plan_prediction.h), for the table's "predicted" column.
std::vector<std::optional<double>> PredictedMeans(const Robot& robot, const std::vector<SimulationPoseSet>& sets,
                                                  const SimulationOptions& study) {
  std::vector<std::optional<double>> predicted;
  for (const SimulationPoseSet& set : sets) {
    const PlanPrediction p = set.random ? PlanPrediction{}
                                        : PredictPlanError(robot, set.poses, study.noise, study.calibration.weighted, {});
    predicted.push_back(p.valid ? std::optional<double>(p.mean_error) : std::nullopt);
  }
  return predicted;
}

// The files `csv` and `plots` would replace: refused without `force`.
Status CheckOutputsFree(const SimulateRequest& request) {
  if (Status s = CheckOutputFree(request.csv, request.force); !s.ok()) return s;
  if (request.plots.empty()) return Status::Ok();
  return charts::CheckChartFilesFree(request.plots, {"fig14", "fig15_mean", "fig15_std"}, request.force);
}

Status CheckRequest(const SimulateRequest& request) {
  if (Status s = request.Check(); !s.ok()) return s;
  return CheckOutputsFree(request);
}

// The table and the figures the request asks for.
Status WriteOutputs(SimulateOutcome* outcome) {
  const SimulateRequest& request = outcome->request;
  if (!request.csv.empty()) {
    if (Status s = WriteTable(request.csv, outcome->result, outcome->sweep); !s.ok()) return s;
  }
  if (request.plots.empty()) return Status::Ok();
  const SweepResult* sweep = outcome->sweep ? &*outcome->sweep : nullptr;
  Status s = WriteFigures(request.plots, outcome->result, sweep, LengthUnitName(outcome->robot.length_unit),
                          &outcome->figures);
  return s;
}

}  // namespace

StatusOr<SimulateOutcome> RunSimulationStudy(SimulateRequest request, const JobHooks& hooks) {
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), request.noise_entries, &request.study.noise, "noise");
      !s.ok())
    return s;
  if (request.weighted) {
    request.study.calibration.weighted = true;
    request.study.calibration.noise = request.study.noise;
  }
  StatusOr<Robot> robot = LoadRobot(request.robot);
  if (!robot.ok()) return robot.status();
  if (Status s = CheckRequest(request); !s.ok()) return s;
  std::optional<std::pair<int, int>> sweep_range;
  if (!request.sweep.empty()) {
    StatusOr<std::pair<int, int>> range = ParseSweep(request.sweep);
    if (!range.ok()) return range.status();
    sweep_range = *range;
  }
  const auto start = std::chrono::steady_clock::now();
  StatusOr<std::vector<SimulationPoseSet>> sets = ResolveSets(*robot, request, hooks);
  if (!sets.ok()) return sets.status();
  hooks.Stage("simulate (runs)");
  StatusOr<SimulationResult> result = Simulate(*robot, *sets, request.study, hooks);
  if (!result.ok()) return result.status();
  SimulateOutcome outcome{request, *robot, std::move(*result), std::nullopt, {}, 0, PredictedMeans(*robot, *sets, request.study)};
  if (sweep_range) {
    hooks.Stage("sweep (runs)");
    StatusOr<SweepResult> swept =
        SimulateSweep(*robot, *sets, sweep_range->first, sweep_range->second, request.study, hooks);
    if (!swept.ok()) return swept.status();
    outcome.sweep = std::move(*swept);
  }
  if (Status s = WriteOutputs(&outcome); !s.ok()) return s;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

nlohmann::json ToJson(const SimulateOutcome& outcome) {
  return ResultJson(outcome.robot, outcome.request, outcome.result, outcome.sweep, outcome.predicted_mean);
}

std::string FormatSimulateSummary(const SimulateOutcome& outcome) {
  std::ostringstream out;
  PrintReport(outcome.robot, outcome.request, outcome.result, outcome.sweep, outcome.predicted_mean, out);
  if (!outcome.request.csv.empty()) out << "table written to " << outcome.request.csv << "\n";
  for (const std::string& figure : outcome.figures) out << "figure written to " << figure << "\n";
  out << "done in " << outcome.seconds << " s\n";
  return out.str();
}

}  // namespace hexcal::workflow

// hexcal simulate --robot R --sets random,boundary,plan.csv[,...] [--poses N] [--runs 100] [--seed S]
//   [--perturb 0.5] [--noise-position 0.001 --noise-angle 0.01 --noise-leg 0.001] [--threads T]
//   [--sweep A:B] [--json] [--csv FILE] [--plots DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "charts/chart_render.h"
#include "charts/figures.h"
#include "core/candidates.h"
#include "core/csv.h"
#include "core/robot_io.h"
#include "core/simulation.h"

namespace hexcal::cli {
namespace {

struct SimulateCliOptions {
  std::string robot, sets = "random,boundary", sweep, csv, plots;
  int poses = 18;
  bool poses_given = false;  // --poses also trims the boundary set
  bool json = false;
  bool force = false;      // replace an existing --csv table or --plots figures
  bool weighted = false;   // calibrate with residuals weighted by the study's noise model
  std::string random_box;  // "x:-5:5,y:-5:5,..." for the random sets
  SimulationOptions study;
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();  // --noise-* over study.noise
};

// --plots DIR: fig14.svg/.png and, with a sweep, fig15_mean and fig15_std
// (charts/figures.h) in DIR, created if missing.
Status WriteFigures(const std::string& directory, const SimulationResult& result, const SweepResult* sweep,
                    const std::string& length_unit, std::vector<std::string>* written) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) return Status::IoError(directory + ": cannot create the plots folder: " + error.message());
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

// The files --csv and --plots would replace: refused without --force.
Status CheckOutputsFree(const SimulateCliOptions& cli) {
  if (Status s = CheckOutputFree(cli.csv, cli.force); !s.ok()) return s;
  if (cli.plots.empty()) return Status::Ok();
  for (const char* name : {"fig14", "fig15_mean", "fig15_std"}) {
    for (const char* extension : {".svg", ".png"}) {
      const std::string path = (std::filesystem::path(cli.plots) / (std::string(name) + extension)).string();
      if (Status s = CheckOutputFree(path, cli.force); !s.ok()) return s;
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
      return Status::Error("--random-box: '" + item + "' is not NAME:MIN:MAX (x, y, z, q1, q2, q3)");
    StatusOr<double> lo = ParseNumber(item.substr(a + 1, b - a - 1)), hi = ParseNumber(item.substr(b + 1));
    if (!lo.ok() || !hi.ok() || !(*lo < *hi))
      return Status::Error("--random-box: '" + item + "' needs finite MIN < MAX");
    box.bounds[index] = Range{*lo, *hi};
  }
  return box;
}

StatusOr<std::pair<int, int>> ParseSweep(const std::string& text) {
  const size_t colon = text.find(':');
  if (colon != std::string::npos) {
    StatusOr<double> lo = ParseNumber(text.substr(0, colon)), hi = ParseNumber(text.substr(colon + 1));
    // Bounds checked before the casts: a double beyond int's range cannot be cast.
    constexpr double kMaxSweepPoses = 10000;
    if (lo.ok() && hi.ok() && *lo >= kParamsPerLeg && *hi >= *lo && *hi <= kMaxSweepPoses && *lo == std::floor(*lo) &&
        *hi == std::floor(*hi)) {
      return std::make_pair(static_cast<int>(*lo), static_cast<int>(*hi));
    }
  }
  return Status::Error("--sweep: '" + text + "' is not MIN:MAX with 7 <= MIN <= MAX <= 10000, e.g. 8:41");
}

// "random" draws poses in every run, "boundary" is the boundary candidate set
// (its first --poses poses when --poses is given), anything else a pose file.
StatusOr<std::vector<SimulationPoseSet>> ResolveSets(const Robot& robot, const SimulateCliOptions& cli) {
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
      ProgressBar progress("boundary poses");
      StatusOr<CandidateSet> boundary =
          GenerateCandidates(robot, options, {[&](int done, int total) { progress.Update(done, total); }});
      if (!boundary.ok()) return boundary.status();
      std::vector<Vector6d> poses = std::move(boundary->poses);
      if (cli.poses_given && static_cast<int>(poses.size()) > cli.poses) poses.resize(cli.poses);
      sets.push_back(FixedPoseSet("boundary", std::move(poses)));
    } else if (name.empty()) {
      return Status::Error("--sets: empty entry in '" + cli.sets + "'");
    } else {
      StatusOr<std::vector<Vector6d>> poses = LoadPoses(name);
      if (!poses.ok()) return poses.status();
      sets.push_back(FixedPoseSet(name, std::move(*poses)));
    }
  }
  return sets;
}

nlohmann::json SetJson(const SetError& set) {
  return {{"name", set.name},
          {"poses", set.poses},
          {"mean", set.mean},
          {"std", set.std},
          {"ratio_to_random", set.ratio_to_random ? nlohmann::json(*set.ratio_to_random) : nlohmann::json(nullptr)},
          {"mean_estimate_error", set.mean_estimate_error},
          {"runs", set.runs},
          {"failed_runs", set.failed_runs}};
}

nlohmann::json ResultJson(const Robot& robot, const SimulateCliOptions& cli, const SimulationResult& result,
                          const std::optional<SweepResult>& sweep) {
  nlohmann::json sets = nlohmann::json::array();
  for (const SetError& set : result.sets) sets.push_back(SetJson(set));
  nlohmann::json j = {{"before", {{"mean", result.before.mean}, {"std", result.before.std}}},
                      {"sets", sets},
                      {"robot", robot.name},
                      {"length_unit", LengthUnitName(robot.length_unit)},
                      {"runs", cli.study.runs},
                      {"seed", cli.study.seed},
                      {"perturb", cli.study.perturb},
                      {"weighted", cli.study.calibration.weighted},
                      {"random_box", cli.random_box},
                      {"noise",
                       {{"position", cli.study.noise.position},
                        {"angle_deg", cli.study.noise.angle_deg},
                        {"leg", cli.study.noise.leg}}}};
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
                 const std::optional<double>& ratio, std::ostream& out) {
  char line[200];
  std::snprintf(line, sizeof line, "%-28s %6s %12.4g %12.4g", name.c_str(), poses.c_str(), mean, std);
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

void PrintReport(const Robot& robot, const SimulateCliOptions& cli, const SimulationResult& result,
                 const std::optional<SweepResult>& sweep, std::ostream& out) {
  const char* unit = LengthUnitName(robot.length_unit);
  const SimulationOptions& study = cli.study;
  out << "section 7 study on robot " << robot.name << ": " << study.runs << " runs, seed " << study.seed << "\n"
      << "true robot: nominal + uniform perturbation within ±" << study.perturb << " " << unit
      << " of each of the 42 parameters\n"
      << "noise (uniform): ±" << study.noise.position << " " << unit << " position, ±" << study.noise.angle_deg
      << " deg angles, ±" << study.noise.leg << " " << unit << " leg readings\n\n"
      << "error |P_est - P_true| over the 42 parameters and all runs (" << unit << ")\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-28s %6s %12s %12s %12s\n", "set", "poses", "mean", "std", "/ random");
  out << line;
  PrintSetRow("before calibration", "-", result.before.mean, result.before.std, std::nullopt, out);
  for (const SetError& set : result.sets) {
    PrintSetRow(set.name, std::to_string(set.poses), set.mean, set.std, set.ratio_to_random, out);
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

int RunSimulate(SimulateCliOptions cli, std::ostream& out, std::ostream& err) {
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), *cli.noise, &cli.study.noise, "noise"); !s.ok())
    return ReportError(err, "simulate", s);
  if (cli.weighted) {
    cli.study.calibration.weighted = true;
    cli.study.calibration.noise = cli.study.noise;
  }
  StatusOr<Robot> robot = LoadRobot(cli.robot);
  if (!robot.ok()) return ReportError(err, "simulate", robot.status());
  std::string error;
  if (!cli.study.IsValid(&error)) return ReportError(err, "simulate", Status::Error(error));
  if (cli.poses < kParamsPerLeg) {
    return ReportError(err, "simulate", Status::Error("--poses must be at least 7, got " + std::to_string(cli.poses)));
  }
  if (Status s = CheckOutputsFree(cli); !s.ok()) return ReportError(err, "simulate", s);
  std::optional<std::pair<int, int>> sweep_range;
  if (!cli.sweep.empty()) {
    StatusOr<std::pair<int, int>> range = ParseSweep(cli.sweep);
    if (!range.ok()) return ReportError(err, "simulate", range.status());
    sweep_range = *range;
  }
  const auto start = std::chrono::steady_clock::now();
  StatusOr<std::vector<SimulationPoseSet>> sets = ResolveSets(*robot, cli);
  if (!sets.ok()) return ReportError(err, "simulate", sets.status());

  StatusOr<SimulationResult> result = [&] {
    ProgressBar progress("simulate (runs)");  // ends its line before the sweep's bar starts
    return Simulate(*robot, *sets, cli.study, {[&](int done, int total) { progress.Update(done, total); }});
  }();
  if (!result.ok()) return ReportError(err, "simulate", result.status());
  std::optional<SweepResult> sweep;
  if (sweep_range) {
    ProgressBar progress("sweep (runs)");
    StatusOr<SweepResult> swept = SimulateSweep(*robot, *sets, sweep_range->first, sweep_range->second, cli.study,
                                                {[&](int done, int total) { progress.Update(done, total); }});
    if (!swept.ok()) return ReportError(err, "simulate", swept.status());
    sweep = std::move(*swept);
  }

  if (!cli.csv.empty()) {
    if (Status s = WriteTable(cli.csv, *result, sweep); !s.ok()) return ReportError(err, "simulate", s.AsFailure());
  }
  std::vector<std::string> figures;
  if (!cli.plots.empty()) {
    const Status s =
        WriteFigures(cli.plots, *result, sweep ? &*sweep : nullptr, LengthUnitName(robot->length_unit), &figures);
    if (!s.ok()) return ReportError(err, "simulate", s.AsFailure());
  }
  if (cli.json) {
    out << ResultJson(*robot, cli, *result, sweep).dump(2) << "\n";
    return kExitOk;
  }
  PrintReport(*robot, cli, *result, sweep, out);
  if (!cli.csv.empty()) out << "table written to " << cli.csv << "\n";
  for (const std::string& figure : figures) out << "figure written to " << figure << "\n";
  out << "done in " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  return kExitOk;
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SimulateCliOptions>();
  CLI::App* sub = app.add_subcommand("simulate", "the section 7 study: parameter error of pose sets (Figs. 14, 15)");
  sub->add_option("--robot", options->robot, "nominal robot file or preset name")->required();
  sub->add_option("--sets", options->sets, "comma-separated: random, boundary or pose CSV files")
      ->capture_default_str();
  CLI::Option* poses = sub->add_option("--poses", options->poses, "poses of the random set (and of boundary if given)")
                           ->check(CountRange(1, 100000))
                           ->capture_default_str();
  sub->add_option("--runs", options->study.runs, "repetitions")->check(CountRange(1, 1000000))->capture_default_str();
  sub->add_option("--seed", options->study.seed, "random seed")->capture_default_str();
  sub->add_option("--perturb", options->study.perturb, "half-width of the parameter perturbation (robot unit)")
      ->capture_default_str();
  AddOptionFlags(sub, NoiseModelOptions(), options->noise, "noise-");
  sub->add_option("--random-box", options->random_box,
                  "draw random sets in this box, e.g. x:-5:5,y:-5:5,z:50:57,q1:-20:20,q2:-20:20,q3:-20:20 "
                  "(intersected with the robot's pose box; the robot's constraints still apply)");
  sub->add_flag("--weighted", options->weighted,
                "calibrate with each residual divided by its standard deviation under the noise model");
  sub->add_option("--threads", options->study.num_threads, "runs at once (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_option("--sweep", options->sweep, "also the error against the number of poses, MIN:MAX (Fig. 15)");
  sub->add_option("--csv", options->csv, "write the table(s) as CSV");
  sub->add_option("--plots", options->plots, "write Fig. 14 (and 15) as SVG and PNG into this folder");
  sub->add_flag("--force", options->force, "overwrite the --csv table and the --plots figures if they exist");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] {
    options->poses_given = poses->count() > 0;
    *exit_code = RunSimulate(*options, std::cout, std::cerr);
  });
}

}  // namespace hexcal::cli

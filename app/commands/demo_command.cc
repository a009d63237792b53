// hexcal demo [--robot inria-left-hand|deltalab-table|FILE] [--out DIR] [--poses 24] [--holdout 8]
//             [--seed 1] [--force] [--json]
//
// The whole calibration flow on a virtual robot and camera (docs/session.md):
//  1. plan N poses with IOOPS (O1 primary, O4 secondary, Tabu 4) among random
//     and boundary candidates the camera can see, against a random set of N;
//  2. record a session folder: a hidden true robot (nominal ± 0.5 mm on every
//     parameter) at unknown camera and target frames, an image rendered at
//     every pose (demo_scene.h) and noisy leg readings, plus random held-out
//     poses;
//  3. measure → register → calibrate → validate (hexcal calibrate --session);
//  4. compare the calibrated parameters with the truth in the registered
//     frames (the gauge, docs/session.md), and write results/report.html.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/demo_scene.h"
#include "app/commands/plan_io.h"
#include "app/commands/session_calibrate.h"
#include "app/commands/session_report.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/identification.h"
#include "core/robot_io.h"
#include "core/registration.h"
#include "core/session.h"

namespace hexcal::cli {
namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  std::string robot = "inria-left-hand";
  std::string out = "hexcal-demo";
  int poses = 24;
  int holdout = 8;
  uint64_t seed = 1;
  bool force = false, json = false;
};

// Prints "[k/5] what ... " lines with the time since the start.
class StepLog {
 public:
  explicit StepLog(std::ostream& out) : out_(out), start_(std::chrono::steady_clock::now()) {}
  void Step(const std::string& what) {
    out_ << "[" << ++step_ << "/5 " << Seconds() << " s] " << what << "\n" << std::flush;
  }
  double Seconds() const {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return std::round(s * 10) / 10;
  }

 private:
  std::ostream& out_;
  std::chrono::steady_clock::time_point start_;
  int step_ = 0;
};

// An existing --out is replaced only with --force and only when it is a demo
// folder (it has truth/frames.yaml) or empty: a user's session is never removed.
Status PrepareOutFolder(const std::string& out, bool force) {
  std::error_code error;
  if (!fs::exists(out, error)) return Status::Ok();
  const bool empty = fs::is_directory(out, error) && fs::is_empty(out, error);
  if (empty) return Status::Ok();
  if (!fs::exists(fs::path(out) / "truth" / "frames.yaml", error))
    return Status::Error(out + ": exists and is not a demo folder; choose another --out");
  if (!force) return Status::Error(out + ": exists; use --force to replace the demo in it");
  fs::remove_all(out, error);
  if (error) return Status::Error(out + ": cannot remove: " + error.message());
  return Status::Ok();
}

struct ParameterComparison {
  double mean = 0, max = 0;                  // |calibrated - truth in the gauge|
  double nominal_mean = 0, nominal_max = 0;  // |nominal - truth in the gauge|
  double within_3sigma = 0;                  // fraction of the parameters with a σ
  int with_sigma = 0;
  nlohmann::json parameters = nlohmann::json::array();  // per parameter: error, σ, error / σ
};

// The truth moved into the registered frames, G = X X*⁻¹ and H = Y Y*⁻¹
// (registration.h), against the calibrated parameters and their σ in report.json.
StatusOr<ParameterComparison> CompareWithTruth(const DemoScene& scene, const std::string& dir,
                                               const nlohmann::json& report) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  if (!config->base_from_camera || !config->platform_from_target)
    return Status::Error(dir + "/session.yaml: no registered frames after the calibration");
  const Robot truth = ExpressInFrames(scene.truth, Compose(*config->base_from_camera, Inverse(scene.base_from_camera)),
                                      Compose(*config->platform_from_target, Inverse(scene.platform_from_target)));
  const ParameterVector true_parameters = ParametersOf(truth);
  const ParameterVector nominal_parameters = ParametersOf(scene.nominal);
  const nlohmann::json& parameters = report.at("parameters");
  if (parameters.size() != static_cast<size_t>(kNumParams))
    return Status::Error(dir + "/results/report.json: expected 42 parameters");
  ParameterComparison c;
  int within = 0;
  for (int k = 0; k < kNumParams; ++k) {
    const nlohmann::json& p = parameters[static_cast<size_t>(k)];
    const double error = std::abs(p.at("estimate").get<double>() - true_parameters[k]);
    const double nominal_error = std::abs(nominal_parameters[k] - true_parameters[k]);
    c.mean += error / kNumParams;
    c.max = std::max(c.max, error);
    c.nominal_mean += nominal_error / kNumParams;
    c.nominal_max = std::max(c.nominal_max, nominal_error);
    nlohmann::json row = {{"leg", p.at("leg")}, {"name", p.at("name")}, {"error", error}, {"sigma", p.at("sigma")}};
    if (p.at("sigma").is_number()) {
      const double sigma = p.at("sigma").get<double>();
      ++c.with_sigma;
      within += error <= 3 * sigma;
      row["error_over_sigma"] = sigma > 0 ? nlohmann::json(error / sigma) : nlohmann::json(nullptr);
    }
    c.parameters.push_back(row);
  }
  c.within_3sigma = c.with_sigma > 0 ? static_cast<double>(within) / c.with_sigma : 0;
  return c;
}

struct DemoPlan {
  size_t candidates = 0;
  PlanResult plan;
  std::vector<Vector6d> held_out;
};

// Step 1: N poses by IOOPS (O1, secondary O4, Tabu 4) among random and boundary
// candidates the camera sees, from a random start; and the held-out poses.
StatusOr<DemoPlan> PlanDemo(const PlanningModel& model, const DemoOptions& options) {
  ProgressBar candidates_progress("candidates");
  StatusOr<CandidatePool> pool =
      BuildCandidatePool(model, "", {"random", "boundary"}, 2000, false, options.seed,
                         [&](int done, int total) { candidates_progress.Update(done, total); });
  if (!pool.ok()) return pool.status();
  StatusOr<std::vector<Vector6d>> initial = InitialPoses(model, "random", options.poses, options.seed);
  if (!initial.ok()) return initial.status();
  StatusOr<std::vector<Vector6d>> held_out = InitialPoses(model, "random", options.holdout, options.seed + 1000);
  if (!held_out.ok()) return held_out.status();
  PlannerOptions planner;
  planner.num_poses = options.poses;
  planner.secondary = Criterion::kO4;
  planner.tabu = 4;
  planner.seed = options.seed;
  ProgressBar plan_progress("planning");
  StatusOr<PlanResult> plan = PlanPoses(model, pool->poses, *initial, planner,
                                        {[&](int done, int total) { plan_progress.Update(done, total); }});
  if (!plan.ok()) return plan.status();
  return DemoPlan{pool->poses.size(), std::move(*plan), std::move(*held_out)};
}

// What `demo --json` prints.
nlohmann::json DemoSummaryJson(const Robot& nominal, const DemoOptions& options, const nlohmann::json& report,
                               const PlanResult& plan, const ParameterComparison& comparison,
                               const std::string& report_path, double seconds) {
  const nlohmann::json& validation = report["validation"];
  const auto pose_errors = [&](const char* when) {
    return nlohmann::json{{"position_rms", validation[when]["position_rms"]},
                          {"orientation_rms", validation[when]["orientation_rms"]}};
  };
  return {{"robot", nominal.name},
          {"length_unit", LengthUnitName(nominal.length_unit)},
          {"session", options.out},
          {"poses", options.poses},
          {"held_out", options.holdout},
          {"usable_images", report["images"].get<int>() - report["unusable_images"].get<int>()},
          {"plan", {{"random", IndicesJson(plan.initial)}, {"selected", IndicesJson(plan.final)}}},
          {"parameter_error",
           {{"mean", comparison.mean},
            {"max", comparison.max},
            {"nominal_mean", comparison.nominal_mean},
            {"nominal_max", comparison.nominal_max}}},
          {"within_3sigma", comparison.within_3sigma},
          {"parameters", comparison.parameters},
          {"validation", {{"before", pose_errors("before")}, {"after", pose_errors("after")}}},
          {"report", report_path},
          {"seconds", seconds}};
}

// The closing lines: parameter error against the truth and held-out pose error.
void PrintDemoSummary(const ParameterComparison& comparison, const nlohmann::json& validation, const char* unit,
                      std::ostream& out) {
  char text[400];
  std::snprintf(text, sizeof text,
                "\nparameter error against the truth (%s): mean %.4g, max %.4g (nominal robot: mean %.4g, max %.4g)\n"
                "within 3 sigma of the truth: %.1f %% of %d parameters\n",
                unit, comparison.mean, comparison.max, comparison.nominal_mean, comparison.nominal_max,
                100 * comparison.within_3sigma, comparison.with_sigma);
  out << text;
  std::snprintf(text, sizeof text,
                "held-out pose error (RMS over %d images, FK against the camera):\n"
                "  before calibration: position %.4g %s, orientation %.4g deg\n"
                "  after calibration:  position %.4g %s, orientation %.4g deg\n",
                validation["rows"].get<int>(), validation["before"]["position_rms"].get<double>(), unit,
                validation["before"]["orientation_rms"].get<double>(),
                validation["after"]["position_rms"].get<double>(), unit,
                validation["after"]["orientation_rms"].get<double>());
  out << text;
}

int RunDemo(const DemoOptions& options, std::ostream& out, std::ostream& err) {
  const char* kCommand = "demo";
  if (options.poses < 8) return ReportError(err, kCommand, Status::Error("--poses must be at least 8"));
  if (options.holdout < 1) return ReportError(err, kCommand, Status::Error("--holdout must be at least 1"));
  StatusOr<Robot> nominal = LoadRobot(options.robot);
  if (!nominal.ok()) return ReportError(err, kCommand, nominal.status());
  // A robot file is written into the session by its absolute path.
  std::error_code error;
  const std::string robot_name =
      fs::exists(options.robot, error) ? fs::absolute(options.robot, error).string() : options.robot;
  StatusOr<Camera> camera = LoadCamera(kSimulatedCameraName);
  if (!camera.ok()) return ReportError(err, kCommand, camera.status(), kExitFailure);
  StatusOr<Target> target = LoadTarget(kDefaultTargetName);
  if (!target.ok()) return ReportError(err, kCommand, target.status(), kExitFailure);
  if (Status s = PrepareOutFolder(options.out, options.force); !s.ok()) return ReportError(err, kCommand, s);

  std::ostream& log = options.json ? err : out;
  StepLog steps(log);
  DemoSceneOptions scene_options;
  scene_options.seed = options.seed;
  const DemoScene scene = MakeDemoScene(*nominal, *camera, *target, scene_options);
  const char* unit = LengthUnitName(nominal->length_unit);

  steps.Step("plan " + std::to_string(options.poses) + " poses (IOOPS: O1, secondary O4, Tabu 4) among random and "
             "boundary candidates with the target in the camera's view");
  const PlanningModel model{*nominal, std::nullopt, scene.view};
  StatusOr<DemoPlan> demo_plan = PlanDemo(model, options);
  if (!demo_plan.ok()) return ReportError(err, kCommand, demo_plan.status(), kExitFailure);
  const PlanResult& plan = demo_plan->plan;
  log << "      " << demo_plan->candidates << " candidates; O1 " << plan.initial.o1 << " -> " << plan.final.o1
      << ", O2 " << plan.initial.o2 << " -> " << plan.final.o2 << " (random set -> plan) in " << plan.iterations
      << " iterations\n";

  steps.Step("record the session in " + options.out + ": hidden true robot (every parameter ±0.5 mm), " +
             std::to_string(options.poses + options.holdout) + " rendered images (" +
             std::to_string(options.holdout) + " held out), leg readings ±" + FormatNumber(scene.noise.leg) + " " +
             unit);
  ProgressBar render_progress("render");
  if (Status s = RecordDemoSession(scene, robot_name, kSimulatedCameraName, plan.poses, demo_plan->held_out,
                                   options.out, [&](int done, int total) { render_progress.Update(done, total); });
      !s.ok())
    return ReportError(err, kCommand, s, kExitFailure);
  // The plan and the planner's indices per iteration, as `hexcal plan --out --history` writes them.
  const SessionPaths paths(options.out);
  if (Status s = WritePlanCsv(paths.plan, model, plan.poses); !s.ok())
    return ReportError(err, kCommand, s, kExitFailure);
  if (Status s = WriteHistoryCsv((fs::path(options.out) / "plan_history.csv").string(), plan); !s.ok())
    return ReportError(err, kCommand, s, kExitFailure);

  steps.Step("measure the images, register the camera and target frames, calibrate, validate (calibrate --session)");
  std::ostringstream calibrate_out;
  if (int code = RunSessionCalibrate(options.out, false, calibrate_out, err); code != kExitOk) return code;
  if (!options.json) {
    std::istringstream lines(calibrate_out.str());
    for (std::string line; std::getline(lines, line);) log << "      " << line << "\n";
  }
  const std::string report_json_path = (fs::path(options.out) / "results" / "report.json").string();
  StatusOr<std::string> report_text = ReadFileToString(report_json_path);
  if (!report_text.ok()) return ReportError(err, kCommand, report_text.status(), kExitFailure);
  const nlohmann::json report = nlohmann::json::parse(*report_text, nullptr, false);
  if (report.is_discarded() || !report["validation"].is_object())
    return ReportError(err, kCommand, Status::Error(report_json_path + ": no validation section"), kExitFailure);

  steps.Step("compare the calibrated parameters with the hidden truth (in the registered frames)");
  StatusOr<ParameterComparison> comparison = CompareWithTruth(scene, options.out, report);
  if (!comparison.ok()) return ReportError(err, kCommand, comparison.status(), kExitFailure);

  steps.Step("write the report");
  const std::string report_path = (fs::path(options.out) / "results" / "report.html").string();
  StatusOr<std::string> html = SessionReportHtml(options.out);
  if (!html.ok()) return ReportError(err, kCommand, html.status(), kExitFailure);
  if (Status s = WriteFileAtomically(report_path, *html); !s.ok()) return ReportError(err, kCommand, s, kExitFailure);

  if (options.json) {
    out << DemoSummaryJson(*nominal, options, report, plan, *comparison, report_path, steps.Seconds()).dump(2) << "\n";
    return kExitOk;
  }
  PrintDemoSummary(*comparison, report["validation"], unit, out);
  out << "report: " << report_path << "\ndone in " << steps.Seconds() << " s\n";
  return kExitOk;
}

}  // namespace

void AddDemoCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand("demo", "the whole calibration flow on a virtual robot and camera");
  sub->add_option("--robot", options->robot, "robot file or preset name (inria-left-hand, deltalab-table)")
      ->capture_default_str();
  sub->add_option("--out", options->out, "session folder to write")->capture_default_str();
  sub->add_option("--poses", options->poses, "planned calibration poses")->capture_default_str();
  sub->add_option("--holdout", options->holdout, "random poses kept out to validate")->capture_default_str();
  sub->add_option("--seed", options->seed, "seed of the truth, the candidates and the noise")->capture_default_str();
  sub->add_flag("--force", options->force, "replace an earlier demo in --out");
  sub->add_flag("--json", options->json, "print one JSON object on stdout (progress on stderr)");
  sub->callback([=] { *exit_code = RunDemo(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

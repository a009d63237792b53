#include "workflow/demo.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/identification.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "report/session_report.h"
#include "session/json_forms.h"
#include "sim/demo_scene.h"
#include "sim/point_demo_scene.h"
#include "workflow/plan_step.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// Log lines "[k/5 t s] what" with the time since the start.
class StepLog {
 public:
  explicit StepLog(const JobHooks& hooks) : hooks_(hooks), start_(std::chrono::steady_clock::now()) {}
  void Step(const std::string& what) {
    std::ostringstream line;
    line << "[" << ++step_ << "/5 " << Seconds() << " s] " << what;
    hooks_.Note(line.str());
  }
  double Seconds() const {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return std::round(s * 10) / 10;
  }

 private:
  const JobHooks& hooks_;
  std::chrono::steady_clock::time_point start_;
  int step_ = 0;
};

// An existing folder is replaced only with `force` and only when it is a demo
// folder (it has truth/frames.yaml) or empty: a user's session is never removed.
Status PrepareOutFolder(const std::string& out, bool force) {
  std::error_code error;
  if (!fs::exists(out, error)) return Status::Ok();
  const bool empty = fs::is_directory(out, error) && fs::is_empty(out, error);
  if (empty) return Status::Ok();
  if (!fs::exists(fs::path(out) / "truth" / "frames.yaml", error))
    return Status::BadInput(out + ": exists and is not a demo folder; choose another --out");
  if (!force) return Status::BadInput(out + ": exists; use --force to replace the demo in it");
  fs::remove_all(out, error);
  if (error) return Status::IoError(out + ": cannot remove: " + error.message());
  return Status::Ok();
}

// The truth moved into the registered frames, G = X X*⁻¹ and H = Y Y*⁻¹
// (registration.h), against the calibrated parameters and their σ.
Status CompareWithTruth(const DemoScene& scene, const std::string& dir, DemoResult* result) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  if (!config->base_from_camera || !config->platform_from_target)
    return Status::Failed(dir + "/session.yaml: no registered frames after the calibration");
  const Robot truth = ExpressInFrames(scene.truth, Compose(*config->base_from_camera, Inverse(scene.base_from_camera)),
                                      Compose(*config->platform_from_target, Inverse(scene.platform_from_target)));
  const ParameterVector true_parameters = ParametersOf(truth);
  const ParameterVector nominal_parameters = ParametersOf(scene.nominal);
  int within = 0;
  for (int k = 0; k < kNumParams; ++k) {
    const ParameterEstimate& p = result->calibration.parameters[k];
    const double error = std::abs(p.estimate - true_parameters[k]);
    const double nominal_error = std::abs(nominal_parameters[k] - true_parameters[k]);
    result->error_mean += error / kNumParams;
    result->error_max = std::max(result->error_max, error);
    result->nominal_error_mean += nominal_error / kNumParams;
    result->nominal_error_max = std::max(result->nominal_error_max, nominal_error);
    result->parameters.push_back({p.leg, p.name, error, p.sigma});
    if (p.sigma) {
      ++result->with_sigma;
      within += error <= 3 * *p.sigma;
    }
  }
  result->within_3sigma = result->with_sigma > 0 ? static_cast<double>(within) / result->with_sigma : 0;
  return Status::Ok();
}

// Step 1 with `random_poses`: N random feasible poses in the camera's view, as
// a plan of no iterations (its indices those of the random set).
StatusOr<PlanResult> RandomDemoPoses(const DemoRequest& request, const PlanningModel& model) {
  StatusOr<std::vector<Vector6d>> poses = InitialPoses(model, "random", request.poses, request.seed);
  if (!poses.ok()) return poses.status().AsFailure();
  PlanResult plan;
  plan.poses = std::move(*poses);
  std::vector<Pose> at;
  for (const Vector6d& pose : plan.poses) at.push_back(model.robot.PoseFromVector(pose));
  plan.initial = plan.final = ComputeIndices(model.robot, at);
  return plan;
}

// Step 1: IOOPS among random and boundary candidates in the camera's view.
StatusOr<PlanResult> PlanDemo(const DemoRequest& request, const PlanningModel& model, const JobHooks& hooks,
                              int* candidates) {
  const std::vector<std::string> kinds =
      request.quick_plan ? std::vector<std::string>{"random"} : std::vector<std::string>{"random", "boundary"};
  StatusOr<CandidatePool> pool = BuildCandidatePool(model, "", kinds, 2000, false, request.seed, hooks);
  if (!pool.ok()) return pool.status().AsFailure();
  *candidates = static_cast<int>(pool->poses.size());
  StatusOr<std::vector<Vector6d>> initial = InitialPoses(model, "random", request.poses, request.seed);
  if (!initial.ok()) return initial.status().AsFailure();
  PlannerOptions planner;
  planner.num_poses = request.poses;
  if (!request.quick_plan) planner.secondary = Criterion::kO4;
  planner.tabu = 4;
  planner.seed = request.seed;
  StatusOr<PlanResult> plan = PlanPoses(model, pool->poses, *initial, planner, hooks);
  if (!plan.ok()) return plan.status().AsFailure();
  return plan;
}

// Step 2: the session folder, with the plan and its history as `hexcal plan` writes them.
// --focal-error: the session's camera file (camera.yaml in the session, named
// by session.yaml) has fx and fy off by that much; the images keep the truth.
Status WriteWrongCamera(const DemoRequest& request, const Camera& truth) {
  if (request.focal_error_percent == 0) return Status::Ok();
  Camera wrong = truth;
  wrong.fx *= 1 + request.focal_error_percent / 100;
  wrong.fy *= 1 + request.focal_error_percent / 100;
  CameraFileExtras extras;
  extras.comment = "hexcal demo --focal-error " + FormatNumber(request.focal_error_percent) +
                   ": fx and fy off by that many percent; the images were rendered with " + kSimulatedCameraName;
  const std::string file = (fs::path(request.out) / "camera.yaml").string();
  if (Status s = SaveCamera(wrong, file, extras); !s.ok()) return s;
  StatusOr<SessionConfig> config = LoadSessionConfig(request.out);
  if (!config.ok()) return config.status();
  config->camera = "camera.yaml";
  return SaveSessionConfig(request.out, *config);
}

Status RecordDemo(const DemoRequest& request, const DemoScene& scene, const PlanningModel& model,
                  const PlanResult& plan, const std::string& robot_name, const JobHooks& hooks) {
  std::vector<Vector6d> held_out;
  if (request.holdout > 0) {
    StatusOr<std::vector<Vector6d>> drawn = InitialPoses(model, "random", request.holdout, request.seed + 1000);
    if (!drawn.ok()) return drawn.status().AsFailure();
    held_out = std::move(*drawn);
  }
  const Status recorded =
      request.instrument == Instrument::kPoints
          ? RecordPointDemoSession(
                scene, PointDemoOptions{request.point_sigma_mm * 1e-3 / MetresPerUnit(scene.nominal.length_unit)},
                robot_name, plan.poses, held_out, request.out)
          : RecordDemoSession(scene, robot_name, kSimulatedCameraName, plan.poses, held_out, request.out,
                              hooks.progress);
  if (!recorded.ok()) return recorded.AsFailure();
  if (Status s = WritePlanCsv(SessionPaths(request.out).plan, model, plan.poses); !s.ok()) return s;
  if (Status s = WriteWrongCamera(request, scene.camera); !s.ok()) return s;
  if (request.random_poses) return Status::Ok();  // no planner iterations to record
  return WriteHistoryCsv((fs::path(request.out) / "plan_history.csv").string(), plan);
}

std::string PlanStepText(const DemoRequest& request) {
  const std::string poses = std::to_string(request.poses);
  const std::string seen = request.instrument == Instrument::kPoints ? " (the tracker sees every reflector)"
                                                                     : " with the target in the camera's view";
  if (request.random_poses) return "draw " + poses + " random feasible poses" + seen;
  return "plan " + poses +
         (request.quick_plan ? " poses (IOOPS: O1, Tabu 4; quick) among random candidates"
                             : " poses (IOOPS: O1, secondary O4, Tabu 4) among random and boundary candidates") +
         seen;
}

// What step 2 records: rendered images, or a tracker's point sets.
std::string RecordedText(const DemoRequest& request, LengthUnit unit) {
  const std::string count = std::to_string(request.poses + request.holdout);
  if (request.instrument == Instrument::kCamera) return count + " rendered images";
  const double sigma = request.point_sigma_mm * 1e-3 / MetresPerUnit(unit);
  return count + " point sets of 4 reflectors (σ " + FormatSignificant(sigma) + " " + LengthUnitName(unit) +
         " per coordinate)";
}

// O1 and O2 with their unit and meaning (issue 39: they were bare numbers).
std::string FormatPlanLine(int candidates, const PlanResult& plan, const std::string& unit) {
  std::ostringstream line;
  line << "      " << candidates << " candidates; O1 " << plan.initial.o1 << " -> " << plan.final.o1 << " " << unit
       << ", O2 " << plan.initial.o2 << " -> " << plan.final.o2 << " (random set -> plan) in " << plan.iterations
       << " iterations (larger is better: O1 the volume of the parameters' uncertainty, in " << unit
       << "; O2 sigma_min / sigma_max, a ratio; hexcal indices says more)";
  return line.str();
}

// Steps 3-5 on the recorded folder: calibrate, compare, report.
Status CalibrateAndCompare(const DemoRequest& request, const DemoScene& scene, StepLog* steps, const JobHooks& hooks,
                           DemoResult* result) {
  const bool from_pixels = request.from_pixels && request.instrument == Instrument::kCamera;
  const bool from_points = request.from_pixels && request.instrument == Instrument::kPoints;
  steps->Step(request.instrument == Instrument::kPoints
                  ? std::string("fit each pose to its points, register the tracker and reflector frames, calibrate, "
                                "validate ") +
                        (from_points ? "(calibrate --session: from the points)" : "(calibrate --session --two-stage)")
                  : std::string("measure the images, register the camera and target frames, calibrate, validate ") +
                        (from_pixels ? "(calibrate --session)" : "(calibrate --session --two-stage)"));
  CalibrateSessionRequest calibrate{request.out};
  calibrate.from_pixels.enabled = from_pixels;
  calibrate.from_points.enabled = from_points;
  StatusOr<CalibrationReport> calibration = CalibrateSession(calibrate, hooks);
  if (!calibration.ok()) return calibration.status();
  std::istringstream lines(FormatCalibrationSummary(*calibration));
  for (std::string line; std::getline(lines, line);) hooks.Note("      " + line);
  if (request.holdout > 0 && !calibration->validation)
    return Status::Failed(CalibrationReportPath(request.out) + ": no validation section");
  result->calibration = *calibration;
  result->usable_images = calibration->usable_images();

  steps->Step("compare the calibrated parameters with the hidden truth (in the registered frames)");
  if (Status s = CompareWithTruth(scene, request.out, result); !s.ok()) return s;
  result->verdict = MakeVerdict(result->calibration, VerdictTruth{result->within_3sigma, result->with_sigma});
  steps->Step("write the report");
  StatusOr<std::string> report = WriteSessionReport({request.out, "", true});
  if (!report.ok()) return report.status().AsFailure();
  result->report = *report;
  return Status::Ok();
}

}  // namespace

StatusOr<DemoResult> RunDemo(const DemoRequest& request, const JobHooks& hooks) {
  if (Status s = request.Check(); !s.ok()) return s;
  StatusOr<Robot> nominal = LoadRobot(request.robot);
  if (!nominal.ok()) return nominal.status();
  // A robot file is written into the session by its absolute path.
  std::error_code error;
  const std::string robot_name =
      fs::exists(request.robot, error) ? fs::absolute(request.robot, error).string() : request.robot;
  StatusOr<Camera> camera = LoadCamera(kSimulatedCameraName);
  if (!camera.ok()) return camera.status().AsFailure();
  StatusOr<Target> target = LoadTarget(kDefaultTargetName);
  if (!target.ok()) return target.status().AsFailure();
  if (Status s = PrepareOutFolder(request.out, request.force); !s.ok()) return s;

  StepLog steps(hooks);
  DemoSceneOptions scene_options;
  scene_options.seed = request.seed;
  const DemoScene scene = MakeDemoScene(*nominal, *camera, *target, scene_options);
  DemoResult result;
  result.robot = nominal->name;
  result.length_unit = LengthUnitName(nominal->length_unit);
  result.session = request.out;
  result.poses = request.poses;
  result.held_out = request.holdout;

  steps.Step(PlanStepText(request));
  // A tracker sees the reflectors from anywhere in the pose box (line of sight is not modelled).
  const PlanningModel model{*nominal, std::nullopt,
                            request.instrument == Instrument::kPoints ? std::nullopt
                                                                      : std::optional<MeasurementConstraints>(scene.view)};
  StatusOr<PlanResult> plan =
      request.random_poses ? RandomDemoPoses(request, model) : PlanDemo(request, model, hooks, &result.plan_candidates);
  if (!plan.ok()) return plan.status();
  if (!request.random_poses) hooks.Note(FormatPlanLine(result.plan_candidates, *plan, result.length_unit));
  result.random_poses = request.random_poses;
  result.from_pixels = request.from_pixels && request.instrument == Instrument::kCamera;
  result.from_points = request.from_pixels && request.instrument == Instrument::kPoints;
  result.instrument = request.instrument;
  result.focal_error_percent = request.focal_error_percent;
  result.random_indices = plan->initial;
  result.plan_indices = plan->final;
  result.plan_iterations = plan->iterations;

  // One length unit per line: the robot's, as the readings' noise beside it.
  const double perturb = scene_options.perturb_m / MetresPerUnit(nominal->length_unit);
  steps.Step("record the session in " + request.out + ": hidden true robot (every parameter ±" +
             FormatSignificant(perturb) + " " + result.length_unit + "), " +
             RecordedText(request, nominal->length_unit) + " (" + std::to_string(request.holdout) +
             " held out), leg readings ±" + FormatNumber(scene.noise.leg) + " " + result.length_unit);
  if (Status s = RecordDemo(request, scene, model, *plan, robot_name, hooks); !s.ok()) return s;
  if (Status s = CalibrateAndCompare(request, scene, &steps, hooks, &result); !s.ok()) return s;
  result.seconds = steps.Seconds();
  return result;
}

nlohmann::json ToJson(const DemoResult& r) {
  nlohmann::json parameters = nlohmann::json::array();
  for (const ParameterError& p : r.parameters) {
    nlohmann::json row = {{"leg", p.leg},
                          {"name", p.name},
                          {"error", p.error},
                          {"sigma", p.sigma ? nlohmann::json(*p.sigma) : nlohmann::json(nullptr)}};
    if (p.sigma) row["error_over_sigma"] = *p.sigma > 0 ? nlohmann::json(p.error / *p.sigma) : nlohmann::json(nullptr);
    parameters.push_back(row);
  }
  const auto pose_errors = [](const PoseErrorStats& s) {
    return nlohmann::json{{"position_rms", s.position_rms}, {"orientation_rms", s.orientation_rms}};
  };
  const std::optional<ValidationSummary>& v = r.calibration.validation;  // none without held-out poses
  const nlohmann::json validation =
      v ? nlohmann::json{{"before", pose_errors(v->before)}, {"after", pose_errors(v->after)}}
        : nlohmann::json(nullptr);
  return {{"robot", r.robot},
          {"length_unit", r.length_unit},
          {"session", r.session},
          {"poses", r.poses},
          {"held_out", r.held_out},
          {"usable_images", r.usable_images},
          {"random_poses", r.random_poses},
          {"from_pixels", r.from_pixels},
          {"from_points", r.from_points},
          {"instrument", InstrumentName(r.instrument)},
          {"focal_error_percent", r.focal_error_percent},
          {"plan", {{"random", IndicesJson(r.random_indices)}, {"selected", IndicesJson(r.plan_indices)}}},
          {"parameter_error",
           {{"mean", r.error_mean},
            {"max", r.error_max},
            {"nominal_mean", r.nominal_error_mean},
            {"nominal_max", r.nominal_error_max}}},
          {"within_3sigma", r.within_3sigma},
          {"parameters", parameters},
          {"validation", validation},
          {"report", r.report},
          {"seconds", r.seconds},
          {"verdict", r.verdict.ToJson()}};
}

std::string FormatDemoSummary(const DemoResult& r) {
  const char* unit = r.length_unit.c_str();
  char text[400];
  std::string out;
  std::snprintf(text, sizeof text,
                "\nparameter error against the truth (%s): mean %.4g, max %.4g (nominal robot: mean %.4g, max %.4g)\n"
                "within 3 sigma of the truth: %.1f %% of %d parameters\n",
                unit, r.error_mean, r.error_max, r.nominal_error_mean, r.nominal_error_max, 100 * r.within_3sigma,
                r.with_sigma);
  out += text;
  if (const std::optional<ValidationSummary>& v = r.calibration.validation) {
    std::snprintf(text, sizeof text,
                  "held-out pose error (RMS over %d %s, FK against the %s):\n"
                  "  before calibration: position %.4g %s, orientation %.4g deg\n"
                  "  after calibration:  position %.4g %s, orientation %.4g deg\n",
                  v->rows, r.instrument == Instrument::kPoints ? "poses" : "images",
                  r.instrument == Instrument::kPoints ? "tracker" : "camera", v->before.position_rms, unit, v->before.orientation_rms, v->after.position_rms, unit,
                  v->after.orientation_rms);
    out += text;
  } else {
    out += "no held-out poses (--holdout 0): `hexcal study --session " + r.session +
           " --select N` validates subsets on the poses they leave out\n";
  }
  return out + r.verdict.ToText() + "report: " + r.report + "\ndone in " + FormatNumber(r.seconds) + " s\n";
}

}  // namespace hexcal::workflow

#include "app/commands/session_calibrate.h"

#include <filesystem>
#include <map>

#include "app/commands/cli_common.h"
#include "core/atomic_file.h"
#include "core/calibration_file.h"
#include "core/csv.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "core/validation.h"
#include "vision/measure.h"

namespace hexcal::cli {
namespace {

namespace fs = std::filesystem;

struct CameraPose {
  bool ok = false;
  Pose camera_from_target;  // target unit
  Matrix6d covariance = Matrix6d::Zero();  // of the pose vector (Euler xyz): target unit², degrees²
};

// measurements.csv rows by image; measures the images missing from it and
// rewrites it with every row (old rows kept as they were).
StatusOr<std::map<std::string, CameraPose>> MeasureSession(const SessionPaths& paths, const std::vector<LegsRow>& legs,
                                                           const Camera& camera, const Target& target,
                                                           const JobHooks& hooks) {
  std::vector<std::vector<std::string>> rows;
  std::map<std::string, CameraPose> poses;
  const std::vector<std::string> columns = ImageMeasurementColumns();
  std::error_code error;
  if (fs::exists(paths.measurements, error)) {
    StatusOr<std::string> text = ReadFileToString(paths.measurements);
    if (!text.ok()) return text.status();
    StatusOr<std::vector<ImageMeasurementRecord>> records = ParseImageMeasurementsCsv(*text, paths.measurements);
    if (!records.ok()) return records.status();
    for (ImageMeasurementRecord& record : *records) {
      poses[record.file] = CameraPose{record.ok, record.camera_from_target, record.covariance};
      rows.push_back(std::move(record.cells));
    }
  }
  std::vector<std::string> missing;
  for (const LegsRow& row : legs)
    if (poses.count(row.image) == 0) missing.push_back((fs::path(paths.images) / row.image).string());
  if (missing.empty()) return poses;
  ProgressBar progress("measure (images)");
  JobHooks bar_and_hooks = hooks;
  bar_and_hooks.progress = [&](int done, int total) {
    progress.Update(done, total);
    hooks.Progress(done, total);
  };
  StatusOr<std::vector<ImageMeasurement>> measured =
      MeasureImages(missing, camera, target, MeasureOptions{}, bar_and_hooks);
  if (!measured.ok()) return measured.status();
  for (ImageMeasurement m : *measured) {
    m.file = fs::path(m.file).filename().string();
    CameraPose pose;
    pose.ok = m.pose.status == PoseStatus::kOk;
    pose.camera_from_target = m.pose.camera_from_target;
    pose.covariance = m.pose.covariance_vector;
    poses[m.file] = pose;
    rows.push_back(ImageMeasurementRow(m));
  }
  if (Status s = WriteFileAtomically(paths.measurements, FormatCsv(columns, rows)); !s.ok()) return s;
  return poses;
}

nlohmann::json StatsJson(const ValidationReport& report) {
  return {{"position_rms", report.position.rms},
          {"position_max", report.position.max},
          {"orientation_rms", report.orientation_deg.rms},
          {"orientation_max", report.orientation_deg.max},
          {"failed", report.failed}};
}

// The rows of legs.csv with a usable target pose: the held-out ones apart,
// the others as the calibration's input (poses and covariances in the robot unit).
struct SessionRows {
  CameraCalibrationInput input;
  std::vector<const LegsRow*> held_out;
  int unusable = 0;  // rows without a usable target pose
};

SessionRows SplitRows(const std::vector<LegsRow>& legs, const std::map<std::string, CameraPose>& poses, double scale,
                      const Pose& fk_start) {
  SessionRows rows;
  for (const LegsRow& row : legs) {
    const CameraPose& pose = poses.at(row.image);
    if (!pose.ok) {
      ++rows.unusable;
      continue;
    }
    if (row.holdout) {
      rows.held_out.push_back(&row);
      continue;
    }
    Pose camera_from_target = pose.camera_from_target;
    camera_from_target.position *= scale;
    rows.input.camera_from_target.push_back(camera_from_target);
    Matrix6d covariance = pose.covariance;  // to the robot unit
    covariance.topRows<3>() *= scale;
    covariance.leftCols<3>() *= scale;
    rows.input.camera_pose_covariance.push_back(covariance);
    rows.input.legs.push_back(row.legs);
    rows.input.fk_start.push_back(fk_start);
  }
  return rows;
}

// FK of the held-out rows with the nominal and the calibrated robot against
// the camera pose mapped into the registered base frame; null without any.
StatusOr<nlohmann::json> ValidateHeldOut(const Robot& nominal, const CameraCalibrationResult& result,
                                         const std::map<std::string, CameraPose>& poses,
                                         const std::vector<const LegsRow*>& held_out, double scale) {
  std::vector<Measurement> validation_rows;
  for (const LegsRow* row : held_out) {
    Pose camera_from_target = poses.at(row->image).camera_from_target;
    camera_from_target.position *= scale;
    Measurement m;
    m.pose = nominal.VectorFromPose(BaseFromPlatform(result.registration, camera_from_target));
    m.legs = row->legs;
    validation_rows.push_back(m);
  }
  if (validation_rows.empty()) return nlohmann::json(nullptr);
  StatusOr<ValidationReport> before = Validate(nominal, validation_rows);
  StatusOr<ValidationReport> after = Validate(result.calibration.robot, validation_rows);
  if (!before.ok()) return before.status();
  if (!after.ok()) return after.status();
  nlohmann::json per_image = nlohmann::json::array();
  for (size_t j = 0; j < held_out.size(); ++j) {
    const ValidationRow &b = before->rows[j], &a = after->rows[j];
    per_image.push_back({{"image", held_out[j]->image},
                         {"position_before", b.ok ? nlohmann::json(b.position_error) : nullptr},
                         {"position_after", a.ok ? nlohmann::json(a.position_error) : nullptr},
                         {"orientation_before", b.ok ? nlohmann::json(b.orientation_error_deg) : nullptr},
                         {"orientation_after", a.ok ? nlohmann::json(a.orientation_error_deg) : nullptr}});
  }
  return nlohmann::json{{"rows", validation_rows.size()},
                        {"before", StatsJson(*before)},
                        {"after", StatsJson(*after)},
                        {"per_image", per_image}};
}

// results/report.json: the rows used, the registration, the calibrated robot
// and parameters with their σ, each leg's fit, the held-out validation.
nlohmann::json SessionReportJson(const std::string& dir, const Robot& nominal, size_t images, const SessionRows& rows,
                                 const CameraCalibrationResult& result, const nlohmann::json& validation,
                                 const std::string& calibrated_path) {
  const Registration& reg = result.registration;
  nlohmann::json full = {
      {"session", dir},
      {"images", images},
      {"unusable_images", rows.unusable},
      {"calibration_images", rows.input.legs.size()},
      {"held_out_images", rows.held_out.size()},
      {"length_unit", LengthUnitName(nominal.length_unit)},
      {"registration",
       {{"position_rms", reg.position_rms},
        {"angle_rms_deg", reg.angle_rms_deg},
        {"position_max", reg.position_max},
        {"angle_max_deg", reg.angle_max_deg}}},
      {"closure_after_calibration",
       {{"position_rms", result.calibrated_position_rms}, {"angle_rms_deg", result.calibrated_angle_rms_deg}}},
      {"validation", validation},
      {"calibrated_robot", calibrated_path}};
  const Vector6d x = VectorFromPose(reg.base_from_camera, EulerConvention::kXYZ);
  const Vector6d y = VectorFromPose(reg.platform_from_target, EulerConvention::kXYZ);
  full["registration"]["base_from_camera"] = std::vector<double>(x.data(), x.data() + 6);
  full["registration"]["platform_from_target"] = std::vector<double>(y.data(), y.data() + 6);
  full["robot"] = RobotJson(result.calibration.robot);
  nlohmann::json parameters = nlohmann::json::array();
  nlohmann::json legs_fit = nlohmann::json::array();
  for (int i = 0; i < kNumLegs; ++i) {
    const LegCalibration& leg = result.calibration.legs[i];
    for (int k = 0; k < kParamsPerLeg; ++k) {
      parameters.push_back({{"leg", i + 1},
                            {"name", ParameterName(k)},
                            {"nominal", leg.initial[k]},
                            {"estimate", leg.estimate[k]},
                            {"sigma", leg.has_uncertainty ? nlohmann::json(leg.std_dev[k]) : nullptr}});
    }
    legs_fit.push_back({{"leg", i + 1},
                        {"variance_factor", leg.variance_factor},
                        {"residual_rms", leg.residual_rms},
                        {"iterations", leg.iterations},
                        {"termination", leg.termination}});
  }
  full["parameters"] = parameters;
  full["legs"] = legs_fit;
  return full;
}

}  // namespace

std::string ResolveSessionFile(const std::string& dir, const std::string& name) {
  std::error_code error;
  const fs::path in_session = fs::path(dir) / name;
  return fs::exists(in_session, error) ? in_session.string() : name;
}

int RunSessionCalibrate(const std::string& dir, bool json, std::ostream& out, std::ostream& err,
                        const JobHooks& hooks) {
  const char* kCommand = "calibrate";
  const SessionPaths paths(dir);
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return ReportError(err, kCommand, config.status());
  StatusOr<std::vector<LegsRow>> legs = LoadSessionLegs(dir);
  if (!legs.ok()) return ReportError(err, kCommand, legs.status());
  const std::string robot_name = ResolveSessionFile(dir, config->robot);
  StatusOr<Robot> nominal = LoadRobot(robot_name);
  if (!nominal.ok()) return ReportError(err, kCommand, nominal.status());
  StatusOr<Camera> camera = LoadCamera(ResolveSessionFile(dir, config->camera));
  if (!camera.ok()) return ReportError(err, kCommand, camera.status());
  StatusOr<Target> target = LoadTarget(ResolveSessionFile(dir, config->target));
  if (!target.ok()) return ReportError(err, kCommand, target.status());
  const std::optional<PoseBox> box = nominal->limits.SamplingBox();
  if (!box || !box->IsComplete())
    return ReportError(err, kCommand, Status::Error(robot_name + ": needs a complete pose_box to start the FK from"));
  Vector6d centre;
  for (int k = 0; k < 6; ++k) centre[k] = box->bounds[k]->Centre();
  const Pose fk_start = nominal->PoseFromVector(centre);

  StatusOr<std::map<std::string, CameraPose>> poses = MeasureSession(paths, *legs, *camera, *target, hooks);
  if (!poses.ok()) return ReportError(err, kCommand, poses.status());
  const double scale = MetresPerUnit(target->length_unit) / MetresPerUnit(nominal->length_unit);

  const SessionRows rows = SplitRows(*legs, *poses, scale, fk_start);
  RegistrationOptions registration;
  registration.position_sigma = config->noise.PositionStdDev();
  registration.angle_sigma_deg = RadToDeg(config->noise.AngleStdDevRad());
  CalibrationOptions calibration;
  // Weighted by each image's own pose covariance and the model's reading
  // noise; σ at least the a priori one (calibration.h, UncertaintyScale).
  calibration.weighted = true;
  calibration.noise = config->noise;
  calibration.uncertainty_scale = UncertaintyScale::kAtLeastAPriori;
  ProgressBar progress("register and calibrate");
  JobHooks bar_and_hooks = hooks;
  bar_and_hooks.progress = [&](int done, int total) {
    progress.Update(done, total);
    hooks.Progress(done, total);
  };
  StatusOr<CameraCalibrationResult> result =
      CalibrateFromCameraPoses(*nominal, rows.input, registration, calibration, bar_and_hooks);
  if (!result.ok()) return ReportError(err, kCommand, result.status(), kExitFailure);
  StatusOr<nlohmann::json> validation = ValidateHeldOut(*nominal, *result, *poses, rows.held_out, scale);
  if (!validation.ok()) return ReportError(err, kCommand, validation.status(), kExitFailure);

  const std::string calibrated_path = (fs::path(paths.results) / "calibrated.yaml").string();
  const std::string used_measurements = (fs::path(paths.results) / "calibration_measurements.csv").string();
  if (Status s = SaveMeasurements(used_measurements, result->measurements); !s.ok())
    return ReportError(err, kCommand, s, kExitFailure);
  const CalibrationInputs inputs{robot_name, used_measurements, calibration, CurrentUtcTimestamp()};
  if (Status s = SaveCalibratedRobot(calibrated_path, result->calibration, inputs); !s.ok())
    return ReportError(err, kCommand, s, kExitFailure);
  config->base_from_camera = result->registration.base_from_camera;
  config->platform_from_target = result->registration.platform_from_target;
  if (Status s = SaveSessionConfig(dir, *config); !s.ok()) return ReportError(err, kCommand, s, kExitFailure);

  const nlohmann::json full =
      SessionReportJson(dir, *nominal, legs->size(), rows, *result, *validation, calibrated_path);
  const std::string report_path = (fs::path(paths.results) / "report.json").string();
  if (Status s = WriteFileAtomically(report_path, full.dump(2) + "\n"); !s.ok())
    return ReportError(err, kCommand, s, kExitFailure);

  if (json) {
    out << full.dump(2) << "\n";
    return kExitOk;
  }
  const char* unit = LengthUnitName(nominal->length_unit);
  const Registration& reg = result->registration;
  out << "session " << dir << ": " << legs->size() << " images, " << rows.input.legs.size() << " for calibration, "
      << rows.held_out.size() << " held out, " << rows.unusable << " without a usable target pose\n"
      << "registration (nominal robot): closure RMS " << reg.position_rms << " " << unit << ", " << reg.angle_rms_deg
      << " deg\n"
      << "after calibration: closure RMS " << result->calibrated_position_rms << " " << unit << ", "
      << result->calibrated_angle_rms_deg << " deg\n";
  if (!validation->is_null()) {
    const auto figure = [&](const char* when, const char* key) { return (*validation)[when][key].get<double>(); };
    out << "held-out validation (position RMS " << unit << ", orientation RMS deg): before "
        << figure("before", "position_rms") << ", " << figure("before", "orientation_rms") << "; after "
        << figure("after", "position_rms") << ", " << figure("after", "orientation_rms") << "\n";
  }
  out << "wrote " << calibrated_path << ", " << report_path << ", frames in " << paths.config << "\n";
  return kExitOk;
}

}  // namespace hexcal::cli

#include "workflow/session_calibrate.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/calibration_file.h"
#include "core/csv.h"
#include "core/reading_units.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "core/sha256.h"
#include "core/staged_folder.h"
#include "core/validation.h"
#include "report/expected_error.h"
#include "session/camera_frame_diagnosis.h"
#include "session/corner_residuals_file.h"
#include "session/results_files.h"
#include "session/session_results.h"
#include "vision/measure.h"
#include "workflow/board_pose_shortfall.h"
#include "workflow/measure_step.h"
#include "workflow/point_session.h"
#include "workflow/session_joint_fit.h"
#include "workflow/session_measure.h"
#include "workflow/session_rows.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

StatusOr<SessionInputs> LoadSessionInputs(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<std::vector<LegsRow>> legs = LoadSessionLegs(dir);
  if (!legs.ok()) return legs.status();
  const std::string robot_name = ResolveSessionFile(dir, config->robot);
  StatusOr<Robot> nominal = LoadRobot(robot_name);
  if (!nominal.ok()) return nominal.status();
  std::vector<LegReadings> readings;
  for (const LegsRow& row : *legs) readings.push_back(row.legs);
  if (Status s = CheckReadingsUnit(*nominal, readings, "row"); !s.ok()) {
    return Status::BadInput(SessionPaths(dir).legs + ": " + s.message());
  }
  if (Status s = CheckRowsNearStroke(*nominal, *legs); !s.ok()) return s.Prefixed(dir + ": ");
  const std::optional<PoseBox> box = nominal->limits.SamplingBox();
  if (!box || !box->IsComplete())
    return Status::BadInput(robot_name + ": needs a complete pose_box to start the FK from");
  const Pose fk_start = nominal->PoseFromVector(WorkspaceCentre(*nominal));
  if (config->instrument == Instrument::kPoints)  // no camera, no target: the points play their part
    return SessionInputs{*config, *legs, robot_name, *nominal, Camera{}, Target{}, fk_start};
  StatusOr<Camera> camera = LoadCamera(ResolveSessionFile(dir, config->camera));
  if (!camera.ok()) return camera.status();
  StatusOr<Target> target = LoadTarget(ResolveSessionFile(dir, config->target));
  if (!target.ok()) return target.status();
  return SessionInputs{*config, *legs, robot_name, *nominal, *camera, *target, fk_start};
}

// A points session's Measure step (point_session.h): every row's pose fitted
// to its points; the session's pose noise then comes from the fits.
StatusOr<CameraPoses> MeasurePointSession(const std::string& dir, SessionInputs* in, const JobHooks& hooks) {
  const SessionConfig& config = in->config;
  // Scaled by hexcal session check-noise's ratio, 1 without.
  StatusOr<PointFiles> files = SessionPointFiles(dir, config);
  if (!files.ok()) return files.status();
  StatusOr<PointPoses> measured = MeasurePointPoses(*files, in->legs, config.noise, hooks);
  if (!measured.ok()) return measured.status();
  const int ok = static_cast<int>(in->legs.size()) - measured->left_out;
  if (ok < kMinBoardPoses)
    return Status::BadInput(dir + ": " + std::to_string(ok) + " poses with fitted points; the calibration needs " +
                            std::to_string(kMinBoardPoses));
  in->config.noise = measured->noise;
  return measured->poses;
}

// The camera pose of every image with readings, measured where
// camera_poses.csv has no valid row (session_measure.h).
StatusOr<CameraPoses> MeasureSession(const std::string& dir, const SessionInputs& in, const ContentHashes& inputs,
                                     const JobHooks& hooks, std::map<std::string, BoardObservation>* observations) {
  std::vector<std::string> images;
  for (const LegsRow& row : in.legs) images.push_back(row.image);
  MeasureSessionOptions options;
  options.known_hashes = &inputs;
  options.keep_observations = observations != nullptr;
  StatusOr<SessionMeasurements> measured = MeasureSessionImages(dir, images, in.camera, in.target, options, hooks);
  if (!measured.ok()) return measured.status();
  std::map<std::string, int> counts;
  int ok = 0;
  for (const auto& [image, pose] : measured->poses) {
    ++counts[pose.status];
    ok += pose.ok ? 1 : 0;
  }
  // A board that fits badly in most images is the target or camera file, not the images.
  if (const std::string diagnosis = DiagnoseBoardFits(counts); !diagnosis.empty()) {
    if (ok < kMinBoardPoses) return Status::BadInput(dir + ": " + diagnosis);
    hooks.Note("warning: " + diagnosis);
  }
  if (ok < kMinBoardPoses)
    return Status::BadInput(dir + ": " + ExplainBoardPoseShortfall(dir, measured->poses, in.target));
  if (observations != nullptr) *observations = std::move(measured->observations);
  return measured->poses;
}

// One image's board pose and covariance, scaled to the robot unit, with its readings.
void AppendCameraRow(const SessionInputs& in, const LegsRow& row, const CameraPose& pose, double scale,
                     CameraCalibrationInput* input) {
  Pose camera_from_target = pose.camera_from_target;
  camera_from_target.position *= scale;
  input->camera_from_target.push_back(camera_from_target);
  Matrix6d covariance = pose.covariance;  // to the robot unit
  covariance.topRows<3>() *= scale;
  covariance.leftCols<3>() *= scale;
  input->camera_pose_covariance.push_back(covariance);
  input->legs.push_back(row.legs);
  input->fk_start.push_back(in.fk_start);
}

SplitRows SplitSessionRows(const SessionInputs& in, const CameraPoses& poses, double scale) {
  SplitRows split;
  for (const LegsRow& row : in.legs) {
    const CameraPose& pose = poses.at(row.image);
    if (!pose.ok) {
      ++split.unusable;
      continue;
    }
    if (row.holdout) {
      split.held_out.push_back(&row);
      continue;
    }
    AppendCameraRow(in, row, pose, scale, &split.input);
    split.calibration_rows.push_back(&row);
  }
  return split;
}

// results/ as one unit (session_results.h): the calibrated robot, the rows it
// was fitted to, report.json and manifest.json go into a fresh folder that is
// swapped in whole; then the registered frames into session.yaml.
Status WriteCalibrationResults(const std::string& dir, const SessionInputs* in, const CameraCalibrationResult& result,
                               const CalibrationOptions& calibration, const CalibrationReport& report,
                               const std::optional<Camera>& fitted_camera, const CornerResidualTable* corners,
                               const PointsResults* points, const ContentHashes& inputs) {
  const SessionPaths paths(dir);
  StatusOr<StagedFolder> staged = StagedFolder::Begin(paths.results);
  if (!staged.ok()) return staged.status();
  const std::string used_measurements = ResultsFile(dir, kUsedMeasurements);
  if (Status s = SaveMeasurements(staged->File(kUsedMeasurements), result.measurements); !s.ok()) return s;
  const CalibrationInputs calibration_inputs{in->robot_name, used_measurements, calibration, CurrentUtcTimestamp()};
  if (Status s = SaveCalibratedRobot(staged->File(kCalibratedRobot), result.calibration, calibration_inputs); !s.ok())
    return s;
  if (Status s = SaveCalibrationReport(staged->File(kReportJson), report); !s.ok()) return s;
  std::vector<const char*> outputs = {kUsedMeasurements, kCalibratedRobot, kReportJson};
  if (fitted_camera) {
    CameraFileExtras extras;
    extras.comment = "The intrinsics hexcal calibrate --session --from-pixels estimated (docs/calibration.md)";
    if (Status s = SaveCamera(*fitted_camera, staged->File(kFittedCamera), extras); !s.ok()) return s;
    outputs.push_back(kFittedCamera);
  }
  if (corners != nullptr) {
    if (Status s = SaveCornerResiduals(staged->File(kCornerResiduals), *corners); !s.ok()) return s;
    outputs.push_back(kCornerResiduals);
  }
  if (points != nullptr) {
    if (Status s = SaveFittedReflectors(staged->File(kFittedReflectors), points->fit); !s.ok()) return s;
    if (Status s = SavePointResiduals(staged->File(kPointResiduals), points->fit, points->poses); !s.ok()) return s;
    outputs.insert(outputs.end(), {kFittedReflectors, kPointResiduals});
  }
  ResultsManifest manifest{calibration_inputs.date, "calibrate --session", inputs, {}};
  for (const char* name : outputs) {
    StatusOr<std::string> hash = Sha256OfFile(staged->File(name), kMaxTableBytes);
    if (!hash.ok()) return hash.status();
    manifest.outputs[name] = *hash;
  }
  if (Status s = WriteFileAtomically(staged->File(kResultsManifest), ManifestToJsonText(manifest)); !s.ok()) return s;
  if (Status s = staged->Publish(); !s.ok()) return s;
  // A copy of report.json's frames, for display; results/ is the record. The
  // file as it is (a points session's noise was replaced by the fits' in `in`).
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  config->base_from_camera = result.registration.base_from_camera;
  config->platform_from_target = result.registration.platform_from_target;
  return SaveSessionConfig(dir, *config);
}

// What was read at the start must still be there: a run whose inputs changed
// underneath it (a writer that ignores the lock) publishes nothing.
Status CheckInputsUnchanged(const std::string& dir, const ContentHashes& before) {
  StatusOr<ContentHashes> now = HashSessionInputs(dir);
  if (!now.ok()) return now.status();
  const std::vector<std::string> changed = DifferingNames(before, *now);
  if (changed.empty()) return Status::Ok();
  return Status::Failed(dir + ": " + ListNames(changed) +
                        " changed while calibrating (another program wrote the session); results/ was left as it "
                        "was: run again");
}

// The session's noise model weighs the closure residuals of the registration.
RegistrationOptions SessionRegistrationOptions(const NoiseModel& noise) { return RegistrationOptionsFromNoise(noise); }

// Asking for the other instrument's joint fit by name is bad input.
Status CheckJointFitRequest(const std::string& dir, const CalibrateSessionRequest& request, Instrument instrument) {
  if (instrument == Instrument::kPoints && request.from_pixels.enabled && !request.from_pixels.fall_back)
    return Status::BadInput(dir + ": a points session has no pixels; --from-points fits the measured points themselves");
  if (instrument == Instrument::kCamera && request.from_points.enabled && !request.from_points.fall_back)
    return Status::BadInput(dir + ": a camera session has no points; --from-pixels fits the tag corners themselves");
  if (instrument == Instrument::kCamera && !request.from_points.estimate_reflectors)
    return Status::BadInput(dir + ": --keep-reflectors is for a points session (a camera session has no reflectors)");
  return Status::Ok();
}

}  // namespace

CalibrationOptions SessionCalibrationOptions(const NoiseModel& noise, const OutlierScreening& outliers) {
  CalibrationOptions calibration;
  calibration.weighted = true;
  calibration.noise = noise;
  calibration.uncertainty_scale = UncertaintyScale::kAtLeastAPriori;
  calibration.outliers = outliers;
  return calibration;
}

namespace {

StatusOr<OpenSession> OpenAndMeasure(const std::string& dir, LockWait wait, const JobHooks& hooks,
                                     bool keep_observations = false) {
  // "DIR/session.yaml: no such file" says more than the lock could.
  if (StatusOr<SessionConfig> config = LoadSessionConfig(dir); !config.ok()) return config.status();
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, wait);  // measuring writes camera_poses.csv
  if (!lock.ok()) return lock.status();
  StatusOr<ContentHashes> hashes = HashSessionInputs(dir);
  if (!hashes.ok()) return hashes.status();
  StatusOr<SessionInputs> in = LoadSessionInputs(dir);
  if (!in.ok()) return in.status();
  std::map<std::string, BoardObservation> observations;
  const bool points = in->config.instrument == Instrument::kPoints;
  StatusOr<CameraPoses> poses = points ? MeasurePointSession(dir, &*in, hooks)
                                       : MeasureSession(dir, *in, *hashes, hooks,
                                                        keep_observations ? &observations : nullptr);
  if (!poses.ok()) return poses.status();
  // The points are in the robot's unit; the board's poses in the target's.
  const double scale = points ? 1 : MetresPerUnit(in->target.length_unit) / MetresPerUnit(in->nominal.length_unit);
  return OpenSession{std::move(*lock), std::move(*hashes), std::move(*in), std::move(*poses), scale,
                     std::move(observations)};
}

// The bias diagnosis (camera_frame_diagnosis.h) with the camera the
// calibration ended with: the board poses of the fitted camera and target
// scale after a calibration from pixels, the session's otherwise.
std::optional<CameraFrameResiduals> CameraFrameDiagnosis(const SessionInputs& in, const SplitRows& split,
                                                         double scale, const CameraCalibrationResult& result,
                                                         const std::optional<PixelOutcome>& from_pixels,
                                                         const CalibrationOptions& calibration,
                                                         const JobHooks& hooks) {
  CameraCalibrationInput input = split.input;
  Camera camera = in.camera;
  double robot_per_target_unit = scale;
  if (from_pixels) {
    for (size_t j = 0; j < input.camera_from_target.size(); ++j)
      if (from_pixels->camera_poses[j]) input.camera_from_target[j] = *from_pixels->camera_poses[j];
    camera = from_pixels->fitted_camera;
    robot_per_target_unit *= from_pixels->target_scale;
  }
  return SessionCameraFrameResiduals(in.nominal, input, result, SessionRegistrationOptions(in.config.noise),
                                     calibration,
                                     SessionBiasModels(camera, in.target, robot_per_target_unit), hooks);
}

// A joint fit (session_joint_fit.h) run on a copy of the two-stage result,
// which it replaces only when it succeeds (and sets `outcome`). When it
// fails, the two-stage calibration stands with a warning, unless the request
// does not fall back or the run was cancelled.
template <typename Outcome, typename Apply>
Status ReplaceTwoStage(bool fall_back, const JobHooks& hooks, const TwoStageResult& two_stage, Apply apply,
                       std::optional<Outcome>* outcome) {
  CameraCalibrationResult result = *two_stage.result;
  std::vector<Measurement> held_out = *two_stage.held_out;
  std::optional<ValidationSummary> validation = *two_stage.validation;
  StatusOr<Outcome> fit = apply(TwoStageResult{&result, &held_out, &validation});
  if (fit.ok()) {
    *two_stage.result = std::move(result);
    *two_stage.held_out = std::move(held_out);
    *two_stage.validation = std::move(validation);
    *outcome = std::move(*fit);
    return Status::Ok();
  }
  if (fit.status().cancelled() || !fall_back) return fit.status();
  hooks.Note("warning: " + fit.status().message() + "; kept the two-stage calibration (--two-stage skips it)");
  return Status::Ok();
}

}  // namespace

StatusOr<CalibrationReport> CalibrateSession(const CalibrateSessionRequest& request, const JobHooks& hooks) {
  const std::string& dir = request.session;
  StatusOr<OpenSession> open = OpenAndMeasure(dir, request.wait, hooks, request.from_pixels.enabled);
  if (!open.ok()) return open.status();
  SessionInputs* in = &open->in;
  const ContentHashes* inputs = &open->hashes;
  const CameraPoses* poses = &open->poses;
  const double scale = open->scale;
  const SplitRows split = SplitSessionRows(*in, *poses, scale);
  if (Status s = CheckNominalFk(in->nominal, in->fk_start, split.calibration_rows); !s.ok()) return s;
  if (Status s = CheckJointFitRequest(dir, request, in->config.instrument); !s.ok()) return s;

  const RegistrationOptions registration = SessionRegistrationOptions(in->config.noise);
  const CalibrationOptions calibration = SessionCalibrationOptions(in->config.noise, request.outliers);
  std::string options_error;
  if (!calibration.IsValid(&options_error)) return Status::BadInput(options_error);
  hooks.Stage("register and calibrate");
  StatusOr<CameraCalibrationResult> result =
      CalibrateFromCameraPoses(in->nominal, split.input, registration, calibration, hooks);
  if (!result.ok()) return result.status().AsFailure();
  std::vector<Measurement> held_out = HeldOutMeasurements(*in, *poses, split.held_out, *result, scale);
  StatusOr<std::optional<ValidationSummary>> validation = ValidateHeldOut(*in, split.held_out, held_out, *result);
  if (!validation.ok()) return validation.status();
  std::optional<PixelOutcome> from_pixels;
  std::optional<PointOutcome> from_points;
  const TwoStageResult two_stage{&*result, &held_out, &*validation};
  // A points session has no pixels: the points' fits are its measurements.
  if (request.from_pixels.enabled && in->config.instrument == Instrument::kCamera) {
    auto fit = [&](const TwoStageResult& copy) {
      return ApplyFromPixels(dir, *open, split, request.from_pixels, request.outliers, hooks, copy);
    };
    if (Status s = ReplaceTwoStage(request.from_pixels.fall_back, hooks, two_stage, fit, &from_pixels); !s.ok())
      return s;
  }
  if (request.from_points.enabled && in->config.instrument == Instrument::kPoints) {
    auto fit = [&](const TwoStageResult& copy) {
      return ApplyFromPoints(dir, *open, split, request.from_points, request.outliers, hooks, copy);
    };
    if (Status s = ReplaceTwoStage(request.from_points.fall_back, hooks, two_stage, fit, &from_points); !s.ok())
      return s;
  }

  CalibrationReport report = MakeReport(dir, *in, split, *result);
  report.validation = *validation;
  if (from_pixels) report.from_pixels = from_pixels->summary;
  if (from_points) report.from_points = from_points->summary;
  report.noise = ExpectedNoise(*in, held_out, result->calibration.robot);
  if (in->config.instrument == Instrument::kCamera)  // the bias along a camera's optical axis
    report.camera_frame_residuals = CameraFrameDiagnosis(*in, split, scale, *result, from_pixels, calibration, hooks);
  if (request.outliers.enabled) {
    report.screening = OutlierScreeningSummary{request.outliers.threshold, request.outliers.keep,
                                               report.calibration_images >= kMinRowsToScreen};
  }
  if (Status s = CheckInputsUnchanged(dir, *inputs); !s.ok()) return s;
  const std::optional<Camera> fitted_camera = from_pixels ? from_pixels->camera : std::nullopt;
  const CornerResidualTable* corners = from_pixels ? &from_pixels->corners : nullptr;
  const PointsResults* points = from_points ? &from_points->results : nullptr;
  if (Status s =
          WriteCalibrationResults(dir, &*in, *result, calibration, report, fitted_camera, corners, points, *inputs);
      !s.ok())
    return s;
  return report;
}

StatusOr<MeasuredSession> LoadMeasuredSession(const std::string& dir, LockWait wait, const JobHooks& hooks) {
  StatusOr<OpenSession> open = OpenAndMeasure(dir, wait, hooks);
  if (!open.ok()) return open.status();
  const SessionInputs* in = &open->in;
  const CameraPoses* poses = &open->poses;
  const double scale = open->scale;
  MeasuredSession session{in->nominal, in->config.noise, {}, {}, {}, 0, open->hashes};
  CameraCalibrationInput input;
  std::vector<const LegsRow*> used;
  for (const LegsRow& row : in->legs) {
    const CameraPose& pose = poses->at(row.image);
    if (!pose.ok) {
      ++session.unusable;
      continue;
    }
    AppendCameraRow(*in, row, pose, scale, &input);
    session.images.push_back(row.image);
    used.push_back(&row);
  }
  if (Status s = CheckNominalFk(in->nominal, in->fk_start, used); !s.ok()) return s;
  const CalibrationOptions calibration = SessionCalibrationOptions(in->config.noise, OutlierScreening{true});
  StatusOr<CameraCalibrationResult> registered = CalibrateFromCameraPoses(
      in->nominal, input, SessionRegistrationOptions(in->config.noise), calibration, {nullptr, hooks.cancel});
  if (!registered.ok()) return registered.status().AsFailure();
  session.registration = registered->registration;
  session.measurements = std::move(registered->measurements);
  return session;
}

}  // namespace hexcal::workflow

#include "workflow/session_joint_fit.h"

#include <filesystem>
#include <map>

#include "core/pose.h"
#include "core/session.h"
#include "workflow/point_session.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// --from-pixels: the images, readings and models the fit needs.
SessionPixelSetup PixelSetup(const std::string& dir, const SessionInputs& in, const SplitRows& split, double scale,
                             const std::map<std::string, BoardObservation>& observations) {
  SessionPixelSetup setup{in.nominal, in.camera, in.target, scale, in.config.noise, {}, {}, split.input.legs, {}};
  const std::string images = SessionPaths(dir).images;
  for (const auto& [image, seen] : observations) setup.known_observations[(fs::path(images) / image).string()] = seen;
  for (const LegsRow* row : split.calibration_rows)
    setup.calibration_images.push_back((fs::path(images) / row->image).string());
  for (const LegsRow* row : split.held_out) setup.held_out_images.push_back((fs::path(images) / row->image).string());
  return setup;
}

// The two-stage figures the report compares the calibration from pixels with.
TwoStageComparison TwoStageFigures(const CameraCalibrationResult& result,
                                   const std::optional<ValidationSummary>& validation) {
  TwoStageComparison two;
  if (validation) {
    two.held_out_position_rms = validation->after.position_rms;
    two.held_out_orientation_rms_deg = validation->after.orientation_rms;
  }
  two.mean_parameter_sigma = result.calibration.StdDevs().mean();
  return two;
}

// The camera poses X·B'·Y⁻¹ of the images, B' from the fitted camera; where
// a board pose failed, the two-stage row is kept.
void MapFittedPoses(const Robot& nominal, const Registration& frames, const std::vector<std::optional<Pose>>& poses,
                    std::vector<Measurement>* rows) {
  for (size_t j = 0; j < rows->size(); ++j) {
    if (poses[j]) (*rows)[j].pose = nominal.VectorFromPose(BaseFromPlatform(frames, *poses[j]));
  }
}

// A joint fit (SessionPixelFit or SessionPointFit) in the two-stage
// result's place: its parameters (with its own screening's outliers); the
// closure, the rows of calibration_measurements.csv and the held-out
// validation then use the poses it fitted (with the fitted camera or
// reflectors). Returns the two-stage figures it replaced, for the report.
template <typename JointFit>
StatusOr<TwoStageComparison> AdoptJointFit(const SessionInputs& in, const SplitRows& split,
                                           const StatusOr<JointFit>& fit, const TwoStageResult& two_stage) {
  if (!fit.ok()) return fit.status().cancelled() ? fit.status() : fit.status().AsFailure();
  CameraCalibrationResult* result = two_stage.result;
  std::vector<Measurement>* held_out = two_stage.held_out;
  std::optional<ValidationSummary>* validation = two_stage.validation;
  const TwoStageComparison replaced = TwoStageFigures(*result, *validation);
  result->calibration = fit->fit.calibration;
  MapFittedPoses(in.nominal, result->registration, fit->calibration_poses, &result->measurements);
  if (Status s = ComputeCalibratedClosure(result); !s.ok()) return s.AsFailure();
  MapFittedPoses(in.nominal, result->registration, fit->held_out_poses, held_out);
  StatusOr<std::optional<ValidationSummary>> again = ValidateHeldOut(in, split.held_out, *held_out, *result);
  if (!again.ok()) return again.status();
  *validation = *again;
  return replaced;
}

}  // namespace

StatusOr<PixelOutcome> ApplyFromPixels(const std::string& dir, const OpenSession& open, const SplitRows& split,
                                       const FromPixelsRequest& request, const OutlierScreening& outliers,
                                       const JobHooks& hooks, const TwoStageResult& two_stage) {
  const SessionInputs& in = open.in;
  StatusOr<SessionPixelFit> fit = FitSessionFromPixels(PixelSetup(dir, in, split, open.scale, open.observations),
                                                       *two_stage.result, request, outliers, hooks);
  StatusOr<TwoStageComparison> replaced = AdoptJointFit(in, split, fit, two_stage);
  if (!replaced.ok()) return replaced.status();
  const bool intrinsics = request.focal || request.principal_point;
  CornerResidualTable corners{{}, std::move(fit->fit.corner_residuals)};
  for (const LegsRow* row : split.calibration_rows) corners.images.push_back(row->image);  // the fit's image order
  return PixelOutcome{SummarizeSessionPixelFit(*fit, *replaced),
                      intrinsics ? std::optional<Camera>(fit->fit.camera) : std::nullopt,
                      fit->fit.camera,
                      fit->fit.target_scale,
                      fit->calibration_poses,
                      std::move(corners)};
}

StatusOr<PointOutcome> ApplyFromPoints(const std::string& dir, const OpenSession& open, const SplitRows& split,
                                       const FromPointsRequest& request, const OutlierScreening& outliers,
                                       const JobHooks& hooks, const TwoStageResult& two_stage) {
  const SessionInputs& in = open.in;
  StatusOr<PointFiles> files = SessionPointFiles(dir, in.config);
  if (!files.ok()) return files.status();
  SessionPointSetup setup{in.nominal, *files, in.config.noise, {}, {}, split.input.legs};
  for (const LegsRow* row : split.calibration_rows) setup.calibration_poses.push_back(row->image);
  for (const LegsRow* row : split.held_out) setup.held_out_poses.push_back(row->image);
  StatusOr<SessionPointFit> fit = FitSessionFromPoints(setup, *two_stage.result, request, outliers, hooks);
  StatusOr<TwoStageComparison> replaced = AdoptJointFit(in, split, fit, two_stage);
  if (!replaced.ok()) return replaced.status();
  PointFitSummary summary = SummarizeSessionPointFit(*fit, *replaced);
  return PointOutcome{std::move(summary), PointsResults{std::move(*fit), std::move(setup.calibration_poses)}};
}

}  // namespace hexcal::workflow

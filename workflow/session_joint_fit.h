// The joint fits that may replace a session's two-stage calibration
// (internal to workflow/; split from session_calibrate.cc, which calls them):
// the calibration from pixels (session_pixels.h) or from points
// (session_points.h), started from the two-stage result, whose parameters,
// closure, held-out validation and rows of calibration_measurements.csv then
// take the poses the joint fit ended with. Each works on copies the caller
// keeps only when it succeeds, so a failed fit can fall back to two-stage.
//
//   StatusOr<PixelOutcome> fit = ApplyFromPixels(dir, open, split, request.from_pixels, request.outliers, hooks,
//                                                TwoStageResult{&result, &held_out, &validation});
//   if (fit.ok()) report.from_pixels = fit->summary;
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/measurements.h"
#include "core/outlier_screening.h"
#include "core/registration.h"
#include "core/status.h"
#include "core/validation.h"
#include "session/corner_residuals_file.h"
#include "session/pixel_fit_summary.h"
#include "session/point_fit_summary.h"
#include "vision/camera.h"
#include "workflow/session_pixels.h"
#include "workflow/session_points.h"
#include "workflow/session_rows.h"

namespace hexcal::workflow {

// What the calibration from points writes to results/: the fitted
// reflectors and every point's residual, named by legs.csv's poses.
struct PointsResults {
  SessionPointFit fit;
  std::vector<std::string> poses;  // the fit's pose order
};

// The two-stage calibration a joint fit replaces, in place: its
// parameters and closure, the held-out rows and their validation.
struct TwoStageResult {
  CameraCalibrationResult* result;
  std::vector<Measurement>* held_out;
  std::optional<ValidationSummary>* validation;
};

// What the calibration from pixels adds to the report and to results/.
struct PixelOutcome {
  PixelFitSummary summary;
  std::optional<Camera> camera;  // with the estimated intrinsics; none when they were kept
  Camera fitted_camera;          // the camera the fit ended with (the file's when kept)
  double target_scale = 1;       // the target's fitted scale
  // camera_from_target of each calibration image (robot unit) with them.
  std::vector<std::optional<Pose>> camera_poses;
  CornerResidualTable corners;  // results/corner_residuals.csv
};

// What the calibration from points adds to the report and to results/.
struct PointOutcome {
  PointFitSummary summary;
  PointsResults results;
};

// The two-stage result replaced by the calibration from pixels: its
// parameters, and the closure, held-out validation and the rows of
// calibration_measurements.csv with the board poses of the fitted camera
// (X·B'·Y⁻¹), which the residual charts compare the calibrated robot with.
StatusOr<PixelOutcome> ApplyFromPixels(const std::string& dir, const OpenSession& open, const SplitRows& split,
                                       const FromPixelsRequest& request, const OutlierScreening& outliers,
                                       const JobHooks& hooks, const TwoStageResult& two_stage);

// The two-stage result replaced by the calibration from points: its
// parameters, and the closure, held-out validation and the rows of
// calibration_measurements.csv with every pose fitted again to the fitted
// reflectors (X·B'·Y⁻¹).
StatusOr<PointOutcome> ApplyFromPoints(const std::string& dir, const OpenSession& open, const SplitRows& split,
                                       const FromPointsRequest& request, const OutlierScreening& outliers,
                                       const JobHooks& hooks, const TwoStageResult& two_stage);

}  // namespace hexcal::workflow

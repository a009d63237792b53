// `calibrate --session DIR` on a points session: the calibration from points
// (core/point_calibration.h) run after the two-stage calibration, which gives
// it the registered frames (the gauge), the start values of the parameters
// and the poses (docs/calibration.md, "Calibration from points"). The
// analogue of session_pixels.h for a laser tracker.
//
// The points are read again from the session's points file (the fits of
// tracker_poses keep poses, not points), each σ scaled by check-noise's factor
// as the two-stage fits'. With the reflectors estimated, every pose —
// calibration and held out — is fitted again to the fitted reflectors, so the
// closure and the validation use what the calibration found.
//
//   StatusOr<SessionPointFit> fit = FitSessionFromPoints(setup, two_stage, FromPointsRequest{}, screening, hooks);
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/noise_model.h"
#include "core/outlier_screening.h"
#include "core/point_calibration.h"
#include "core/registration.h"
#include "core/status.h"
#include "session/point_fit_summary.h"
#include "workflow/point_session.h"

namespace hexcal::workflow {

// The calibration from points is the default for a points session, as the
// calibration from pixels is for a camera session (docs/calibration.md).
struct FromPointsRequest {
  bool enabled = true;  // false: the two-stage calibration alone (--two-stage)
  // When the fit fails, keep the two-stage calibration with a note; false
  // (--from-points given explicitly): the failure is the calibration's.
  bool fall_back = true;
  bool estimate_reflectors = true;  // false (--keep-reflectors): the reflectors stay as given
};

// What the fit needs of the session: the poses in the order of the two-stage
// calibration's measurements, and the held-out ones.
struct SessionPointSetup {
  Robot nominal;
  PointFiles files;                                            // with check-noise's factor
  NoiseModel noise;                                            // session.yaml's: the readings' σ
  std::vector<std::string> calibration_poses, held_out_poses;  // legs.csv's pose names
  std::vector<LegReadings> calibration_legs;
};

struct SessionPointFit {
  PointCalibrationResult fit;
  // The reflectors in the reflector frame (the file's, or the estimate's from
  // the poses): as given, and as fitted with the σ of x, y, z.
  std::vector<NamedPoint> given, fitted;
  std::vector<Eigen::Vector3d> fitted_sigma;
  bool from_file = true;  // the given reflectors come from a reflector file
  // The fitted shape's RMS distance from its centroid over the given one's, with σ.
  double scale = 1, scale_sigma = 0;
  // tracker_from_reflectors of every pose fitted again to its points with the
  // fitted reflectors (robot unit); nullopt where that fit fails.
  std::vector<std::optional<Pose>> calibration_poses, held_out_poses;
};

// With `screening` enabled, the readings are screened on the fit itself as
// the calibration from pixels screens them (core/outlier_screening.h,
// ScreenJointFitReadings): a robust fit first, then least squares without the
// outliers (or with them, `keep`), which are named in its legs.
StatusOr<SessionPointFit> FitSessionFromPoints(const SessionPointSetup& setup, const CameraCalibrationResult& two_stage,
                                               const FromPointsRequest& request, const OutlierScreening& screening,
                                               const JobHooks& hooks = {});

// The summary for report.json, with the two-stage figures to compare.
PointFitSummary SummarizeSessionPointFit(const SessionPointFit& fit, const TwoStageComparison& two_stage);

// results/reflectors.csv: point,x,y,z (a reflector file the session can use)
// then sigma_x,sigma_y,sigma_z, in the reflector frame, robot unit.
Status SaveFittedReflectors(const std::string& path, const SessionPointFit& fit);
// results/point_residuals.csv: pose,point,dx,dy,dz,sigma — predicted −
// measured in the tracker frame, robot unit, for every point of the fit.
Status SavePointResiduals(const std::string& path, const SessionPointFit& fit,
                          const std::vector<std::string>& pose_names);

}  // namespace hexcal::workflow

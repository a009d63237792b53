// Calibration from pixels: the 42 kinematic parameters fitted to the tag
// corners themselves, not to board poses computed from them first
// (docs/calibration.md, "Calibration from pixels").
//
// One least-squares problem (Ceres, Levenberg–Marquardt) over
//   - the 42 parameters (a_i, b_i, l_i);
//   - the platform pose A_j of every image (base_from_platform), tied to the
//     image's leg readings;
//   - optionally a common scale φ of the focal lengths (fx, fy = φ fx0, φ fy0),
//     the principal point (cx, cy) and the target's scale s;
// with two kinds of residual:
//   - each tag's 4 corners: the reprojection error of X⁻¹ · A_j · Y · (s P)
//     through the camera model (distortion as in the camera file), whitened
//     by the corners' 8×8 covariance from the edge fit (0.1 px independent
//     where the corners were not refined);
//   - each leg reading: (|A_j b_i − a_i| − (l_i + L_ij)) / σ_L, σ_L the
//     reading noise's standard deviation.
// X = base_from_camera and Y = platform_from_target stay fixed where the
// two-stage registration put them: they fix the gauge (the 12 rigid
// freedoms of base and platform frames, docs/session.md, "The gauge"), so the
// results are in the same frames as the two-stage calibration's.
//
// Uncertainty: the covariance of the 42 parameters and of the camera and
// target quantities is the inverse of JᵀJ with the pose blocks eliminated
// (Schur complement), scaled by max(1, s²), s² = Σ r² / (m − n) the variance
// factor (as calibrate's kAtLeastAPriori): the a priori covariance, larger
// when the data scatter more than the corner and reading noise say.
//
//   PixelCalibrationInput input{nominal, start, camera, target_to_robot, X, Y, images};
//   StatusOr<PixelCalibrationResult> fit = CalibrateFromPixels(input, PixelCalibrationOptions{});
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/job_hooks.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"
#include "vision/camera.h"
#include "vision/corner_diagnostics.h"
#include "vision/detection.h"

namespace hexcal {

struct PixelCalibrationOptions {
  bool estimate_focal = true;             // a common scale of fx and fy
  bool estimate_principal_point = false;  // cx, cy
  bool estimate_target_scale = false;     // the printed board's scale
  double leg_sigma = 0.001;               // standard deviation of a leg reading, robot unit (> 0)
  double corner_sigma_px = 0.1;           // of a corner without an edge-fit covariance, pixels (> 0)
  // > 0: a Cauchy loss of this many σ_L on the leg residuals, so that one
  // wrong reading cannot pull the fit (the screening pass; 0: least squares).
  double leg_cauchy_scale = 0;
  int max_iterations = 100;               // Levenberg–Marquardt iterations
  // 1: Ceres sums the cost and gradient of a multi-threaded evaluation in the
  // order its threads finish, so the result would differ in the 8th digit from
  // run to run; one thread keeps every calibration and report reproducible.
  int num_threads = 1;  // 0: every core

  bool IsValid(std::string* error) const;
};

// One image: its corners, its readings and where the platform starts.
struct PixelImage {
  BoardObservation observation;  // target points in the target unit, pixels
  LegReadings legs;              // robot unit
  Pose base_from_platform;       // start value (e.g. X B_j Y⁻¹ of the two-stage calibration)
  // Readings left out (outliers found by the two-stage screening), by leg.
  std::array<bool, kNumLegs> leg_excluded = {};
};

struct PixelCalibrationInput {
  Robot nominal;           // the parameters' "initial" values in the result
  Robot start;             // the start of the fit (the two-stage calibration)
  Camera camera;           // intrinsics and distortion as in the camera file
  double target_to_robot;  // robot unit per target unit
  Pose base_from_camera;   // X, fixed (the gauge)
  Pose platform_from_target;  // Y, fixed (the gauge)
  std::vector<PixelImage> images;
};

// A camera or target quantity the fit estimated, with its σ.
struct PixelExtraEstimate {
  std::string name;  // "fx", "fy", "cx", "cy" (pixels), "target_scale" (1 = as in the file)
  double file_value = 0;
  double estimate = 0;
  double sigma = 0;
};

// A correlation of two estimated quantities ("focal", "cx", "cy",
// "target_scale", or a parameter "leg 3 az").
struct PixelCorrelation {
  std::string first, second;
  double correlation = 0;
};

struct PixelCalibrationResult {
  CalibrationResult calibration;  // the 42 parameters with covariance, per leg
  Camera camera;                  // with the estimated intrinsics
  double target_scale = 1;        // estimated, or 1
  std::vector<PixelExtraEstimate> extras;
  // Correlations of the extras with each other and with the 42 parameters
  // above 0.95 in magnitude: what the data can hardly separate.
  std::vector<PixelCorrelation> strong_correlations;
  std::vector<Pose> base_from_platform;  // the fitted pose of every image
  // Per image and leg: z = −r = ((l + L) − |A b − a|) / σ_L at the fit
  // (positive: the reading is longer than the pose implies); NaN where excluded.
  std::vector<LegReadings> leg_z;
  int corners = 0, leg_rows = 0;
  double reprojection_rms_px = 0;  // unwhitened, over every corner
  // Every corner's unwhitened residual at the fit; `image` indexes input.images.
  std::vector<CornerResidual> corner_residuals;
  double leg_residual_rms = 0;     // robot unit, over every leg reading used
  double variance_factor = 0;      // s² = Σ r² / (m − n)
  int iterations = 0;
  std::string termination;  // Ceres's, e.g. "CONVERGENCE"
};

// Fails with the reason for invalid options, fewer than 7 images, an image
// without corners, non-finite input, or a solve that does not converge;
// Status::Cancelled when hooks.cancel is raised.
StatusOr<PixelCalibrationResult> CalibrateFromPixels(const PixelCalibrationInput& input,
                                                     const PixelCalibrationOptions& options,
                                                     const JobHooks& hooks = {});

}  // namespace hexcal

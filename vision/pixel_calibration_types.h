// The options, input and result of the calibration from pixels
// (pixel_calibration.h, which has the model, the uncertainty and the usage),
// apart from it so that the problem's summary (pixel_calibration_covariance.h)
// can use them without including the function that builds the problem, as
// core/point_calibration_types.h does for the calibration from points.
//
//   PixelCalibrationOptions options;
//   options.estimate_principal_point = true;  // cx, cy beside the focal scale
//   PixelCalibrationInput input{nominal, start, camera, target_to_robot, X, Y, images};
//   StatusOr<PixelCalibrationResult> fit = CalibrateFromPixels(input, options);
//   for (const PixelExtraEstimate& e : fit->extras) Print(e.name, e.estimate, e.sigma);
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/joint_fit_settings.h"
#include "core/pose.h"
#include "core/robot.h"
#include "vision/camera.h"
#include "vision/corner_diagnostics.h"
#include "vision/detection.h"

namespace hexcal {

struct PixelCalibrationOptions : JointFitSettings {
  bool estimate_focal = true;             // a common scale of fx and fy
  bool estimate_principal_point = false;  // cx, cy
  bool estimate_target_scale = false;     // the printed board's scale
  double corner_sigma_px = 0.1;           // of a corner without an edge-fit covariance, pixels (> 0)

  bool IsValid(std::string* error) const {
    if (!JointFitSettings::IsValid(error)) return false;
    if (!(corner_sigma_px > 0) || !std::isfinite(corner_sigma_px)) {
      if (error) *error = "corner_sigma_px must be positive";
      return false;
    }
    return true;
  }
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
  Robot nominal;              // the parameters' "initial" values in the result
  Robot start;                // the start of the fit (the two-stage calibration)
  Camera camera;              // intrinsics and distortion as in the camera file
  double target_to_robot;     // robot unit per target unit
  Pose base_from_camera;      // X, fixed (the gauge)
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
  double leg_residual_rms = 0;  // robot unit, over every leg reading used
  double variance_factor = 0;   // s² = Σ r² / (m − n)
  int iterations = 0;
  std::string termination;  // Ceres's, e.g. "CONVERGENCE"
};

}  // namespace hexcal

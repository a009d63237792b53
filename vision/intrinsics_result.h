// What an intrinsic calibration found (intrinsics.h has the method and the
// usage): the camera with its σ, each view's use and RMS, every corner's
// residual and the cross-validation of two halves of the views. Apart from
// intrinsics.h so that the judgement of a result (intrinsics_diagnosis.h),
// which CalibrateIntrinsics makes, can read it without including the function
// that makes it.
//
//   StatusOr<IntrinsicsResult> result = CalibrateIntrinsics(files, target, IntrinsicsOptions{});
//   for (const CalibrationView& view : result->views)
//     if (!view.used) std::cout << view.file << ": " << view.reason << "\n";
//   std::cout << DescribeCrossValidation(result->cross_validation) << "\n";
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "vision/camera.h"
#include "vision/corner_diagnostics.h"

namespace hexcal {

struct CalibrationView {
  std::string file;
  int tags = 0;
  bool used = false;
  std::string reason;                    // why not used: "2 target tags", "outlier: RMS 1.9 px > 0.6 px"
  double rms_px = 0;                     // reprojection RMS in the final calibration (used views)
  std::vector<Eigen::Vector2d> corners;  // detected target corners (coverage)
};

// Cross-validation as mrcal does it: the used views split into two disjoint
// halves (alternate views), each calibrated alone, and the two cameras
// compared (vision/intrinsics_diagnosis.h). A difference far above what the
// halves' own σ allow means the model or the data cannot be trusted.
struct CrossValidation {
  bool done = false;  // needs at least 2 × 3 used views
  int views_a = 0, views_b = 0;
  double rms_px = 0;  // |project_a(ray) − project_b(ray)| over a 16 × 12 grid of the image, RMS
  double max_px = 0;  // ... and its largest value
  // |a − b| / sqrt(σa² + σb²) for fx, fy, cx, cy; empty without σ (kPinholeEqui).
  std::vector<double> z;
  double max_z = 0;  // largest of z; 0 when z is empty
};

struct IntrinsicsResult {
  Camera camera;
  // Standard deviations in the order of camera.ParameterNames(); empty when
  // the model's calibration does not estimate them (kPinholeEqui).
  std::vector<double> std_dev;
  double rms_px = 0;  // over every corner of the used views
  int used_views = 0;
  std::vector<CalibrationView> views;  // in the order of the files
  // Every corner of the used views at the final calibration; `image`
  // indexes `views` (corner_diagnostics.h).
  std::vector<CornerResidual> corner_residuals;
  CrossValidation cross_validation;
};

}  // namespace hexcal

// Camera intrinsics from images of the target (cv::calibrateCamera, or
// cv::fisheye::calibrate for the fisheye).
//
// 1. Detection on every image (both cores); a view is usable with at least
//    min_tags_per_view target tags. All images must have one size.
// 2. Calibration of fx, fy, cx, cy and the model's coefficients (camera.h):
//    kRadTan k1 k2 p1 p2 k3 and kRational k1..k6 p1 p2 by cv::calibrateCamera,
//    with the standard deviation of each (σ² (JᵀJ)⁻¹ at the optimum);
//    kPinholeEqui k1..k4 by cv::fisheye::calibrate (CALIB_RECOMPUTE_EXTRINSIC
//    | CALIB_FIX_SKEW), which gives no standard deviations. The RMS figures
//    are hexcal's own, from the solution's poses and Camera::Project, the
//    same for every model: √(Σ|e|² / corners) overall and per view.
// 3. Outlier views: while the worst view's RMS exceeds
//    max(outlier_factor × median view RMS, outlier_min_rms_px), it is dropped
//    and the calibration repeated (never below min_views).
// 4. With the distortion now known, every usable image is detected again with
//    the edge fit in the undistorted image (straight edges are straight only
//    there) and the calibration repeated: `refinement_passes` times.
//
//   StatusOr<IntrinsicsResult> result = CalibrateIntrinsics(files, target, IntrinsicsOptions{});
//   if (result.ok()) SaveCamera(result->camera, "camera.yaml", ExtrasOf(*result));
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/status.h"
#include "vision/camera.h"
#include "vision/detection.h"
#include "vision/intrinsics_result.h"
#include "vision/target.h"

namespace hexcal {

struct IntrinsicsOptions {
  DetectorOptions detector;
  int threads = 2;                           // images detected in parallel, 0..64; 0: every core
  int min_tags_per_view = 4;                 // fewer: the view is not used
  int min_views = 8;                         // fewer usable views: error
  double outlier_factor = 3.0;               // a view's RMS over this × the median RMS ...
  double outlier_min_rms_px = 0.5;           // ... and over this is an outlier,
  double far_outlier_factor = 10.0;          // ... as is one over this × the median, whatever its RMS
  bool keep_outliers = false;                // leave no view out as an outlier (they are still named)
  int refinement_passes = 1;                 // re-detections with the estimated distortion
  CameraModel model = CameraModel::kRadTan;  // distortion model to estimate (camera.h)
  double max_rms_px = 1.0;                   // a larger final RMS is an error (vision/intrinsics_diagnosis.h)

  bool IsValid(std::string* error) const;
};

// hooks.Progress(done, total) over every detection pass (images × passes);
// hooks.cancel stops at the next image (Status::Cancelled).
StatusOr<IntrinsicsResult> CalibrateIntrinsics(const std::vector<std::string>& files, const Target& target,
                                               const IntrinsicsOptions& options, const JobHooks& hooks = {});

// The same from images already in memory (tests); `names` label them.
StatusOr<IntrinsicsResult> CalibrateIntrinsicsFromImages(const std::vector<cv::Mat>& images,
                                                         const std::vector<std::string>& names, const Target& target,
                                                         const IntrinsicsOptions& options, const JobHooks& hooks = {});

// What to write beside the camera in its file.
CameraFileExtras ExtrasOf(const IntrinsicsResult& result);

// A picture of where the corners of the used views fell (one colour per view),
// the outliers in grey, on the image's frame with a 4 × 4 grid and the
// fraction of grid cells that saw a corner. CV_8UC3, image size.
cv::Mat CoverageImage(const IntrinsicsResult& result);
// Fraction of the 8 × 6 image cells holding at least one used corner.
double CoverageFraction(const IntrinsicsResult& result);

}  // namespace hexcal

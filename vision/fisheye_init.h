// A starting camera for the equidistant (fisheye) calibration, from the
// views' corners alone.
//
// cv::fisheye::calibrate starts from f = max(width, height) / π and the image
// centre, then alternates the views' poses and the intrinsics. For a lens
// wider than that guess the first poses are far off, and the alternation
// ends at a reprojection error of hundreds of pixels (six real TUM VI frames:
// 480 px). Here the principal point is taken at the image centre and the focal
// length searched: for each trial f every view's corners are unprojected
// through the equidistant model without distortion (θ = r / f), its pose
// solved from those rays, and the corners reprojected; the f whose views fit
// best (median of the views' RMS) is refined by a golden-section search
// (docs/vision.md, "Fisheye intrinsics from the images alone").
//
//   std::optional<FisheyeStart> start = EquidistantStart(views, cv::Size(1024, 1024));
//   if (start) k = start->CameraMatrix();  // then CALIB_USE_INTRINSIC_GUESS
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "vision/detection.h"

namespace hexcal {

struct FisheyeStart {
  double f = 0;          // px, both axes
  double cx = 0, cy = 0;  // px, the image centre in OpenCV's pixel convention
  double median_rms_px = 0;  // the views' median reprojection RMS at f, k = 0

  cv::Matx33d CameraMatrix() const { return {f, 0, cx, 0, f, cy, 0, 0, 1}; }
};

// The reprojection RMS (px) of one view's corners through an equidistant
// camera (f, c, no distortion), its pose solved from the corners' rays; +inf
// when fewer than 6 corners lie within 75° of the axis.
double EquidistantViewRms(const BoardObservation& view, double f, const cv::Point2d& centre);

// nullopt when no view has 6 corners to solve a pose from.
std::optional<FisheyeStart> EquidistantStart(const std::vector<const BoardObservation*>& views, cv::Size size);

}  // namespace hexcal

// Sub-pixel corners of a tag's black square from its four edges.
//
// AprilTag fits its quad to a thresholded contour, which leaves corners a
// tenth of a pixel or more off, and straight lines in a distorted image are
// curves. Here every edge is a straight line in the ideal (undistorted) image;
// the pixels in a band across it are fitted with a blurred step,
//
//   I(p) = a + b · Φ(d(p) / s),   d(p) = n(θ) · ideal(p) − ρ,
//
// by Levenberg–Marquardt over (θ, ρ, a, b, s): a and b are the local black
// level and contrast, s the blur, Φ the normal CDF. The profile is symmetric
// about the edge, so the fitted line does not depend on blur, and lighting
// that varies slowly along the edge only rescales it. Adjacent lines meet at
// the corners, which are mapped back into the distorted image.
//
// The band keeps inside the black border (one or two bit cells deep) and clear of the
// corners, so the tag's data bits and the neighbouring edges stay out of it.
//
//   std::array<Eigen::Vector2d, 4> corners = ...;  // AprilTag order, OpenCV pixels
//   std::optional<RefinedTag> refined = RefineTagCorners(gray, &ideal_map, /*width_at_border=*/8, /*border_bits=*/1, corners);
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "vision/camera.h"

namespace hexcal {

struct EdgeFit {
  Eigen::Vector2d midpoint = Eigen::Vector2d::Zero();  // ideal pixels, near the edge's middle
  double angle = 0;   // of the normal n, which points from the black square out; radians
  double offset = 0;  // the line: n · (q − midpoint) = offset, ideal pixels
  // Covariance of (angle, offset): σ² (JᵀJ)⁻¹ of the fit, σ² its residual variance.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  double black = 0, contrast = 0, blur = 0;  // grey levels, grey levels, ideal pixels
  double rms = 0;                            // grey levels
  int pixels = 0;
  Eigen::Vector2d Normal() const { return {std::cos(angle), std::sin(angle)}; }
};

struct RefinedTag {
  std::array<Eigen::Vector2d, 4> corners;  // OpenCV convention, AprilTag order, distorted image
  // Covariance of (u0, v0, u1, v1, u2, v2, u3, v3), pixels²: the edges' fits
  // propagated through the intersections and the distortion. Corners that
  // share an edge are correlated, which a pose fit must know to get its own
  // covariance right.
  Eigen::Matrix<double, 8, 8> covariance = Eigen::Matrix<double, 8, 8>::Zero();
  std::array<EdgeFit, 4> edges;  // edge k runs from corner k to corner k+1
};

// The refined corners of a tag whose approximate corners (OpenCV convention,
// AprilTag order) are `corners`; nullopt when the tag is too small (black border
// under 3.5 px deep), an edge has too few pixels, a fit fails, or a corner would
// move more than 2 px; `failure` (may be null) then says which, for a person
// ("edge 2: blur 3.10 px too wide for its 5.20 px cell"). `ideal` may be null:
// the image is then taken as undistorted.
// `border_bits`: the black border's depth in cells (2 on Kalibr's aprilgrid),
// which bounds the band across each edge.
std::optional<RefinedTag> RefineTagCorners(const cv::Mat& gray, const IdealPixelMap* ideal, int width_at_border,
                                           int border_bits, const std::array<Eigen::Vector2d, 4>& corners,
                                           std::string* failure = nullptr);

}  // namespace hexcal

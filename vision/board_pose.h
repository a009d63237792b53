// camera_from_target of one image from every detected corner of the target.
//
// 1. IPPE (cv::solvePnPGeneric, SOLVEPNP_IPPE) on all corners gives the two
//    poses a plane can have; both are refined by Levenberg–Marquardt on the
//    reprojection error (cv::solvePnPRefineLM) with the full distortion model.
//    OpenCV's PnP does not take the fisheye (kPinholeEqui): for it both steps
//    run on the corners undistorted by Camera::Undistort, with an identity
//    camera matrix; step 3 then works in pixels with Camera::Project.
// 2. The better one is kept; if the other explains the corners almost as well
//    (RMS ratio under ambiguity_ratio) the pose is ambiguous: the target is
//    too small or too far for perspective to tell the two apart.
// 3. The best pose is polished by Gauss–Newton on the residuals whitened
//    with each tag's corner covariance C_t from the edge fit (corners that
//    share an edge are correlated; corners AprilTag placed are taken as
//    independent, 0.1 px). Its covariance is Σ = s² (J_wᵀ J_w)⁻¹, J_w the
//    Jacobian of the whitened residuals with respect to a local perturbation
//    R ← Exp(δ) R, t ← t + ε (δ in radians, in the camera frame), and
//    s² = |r_w|² / (2N − 6) the variance factor (≈ 1 when the corner
//    covariances describe the residuals). Σ is also given for the pose vector
//    [x, y, z, q1, q2, q3] (docs/conventions.md).
//
//   BoardPose pose = EstimateBoardPose(camera, observation, BoardPoseOptions{});
//   if (pose.status == PoseStatus::kOk) Use(pose.camera_from_target);
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/pose.h"
#include "vision/camera.h"
#include "vision/detection.h"
#include "vision/target.h"

namespace hexcal {

// Also the status of a measured image (vision/measure.h), hence unreadable and wrong_size.
enum class PoseStatus { kOk, kNoTarget, kTooFewTags, kHighRms, kAmbiguous, kFailed, kUnreadable, kWrongSize };
const char* PoseStatusName(PoseStatus status);  // "ok", "no_target", "too_few_tags", ...

struct BoardPoseOptions {
  int min_tags = 4;              // fewer target tags: too_few_tags
  double max_rms_px = 1.0;       // larger reprojection RMS: high_rms
  double ambiguity_ratio = 1.5;  // second IPPE solution's RMS / best RMS under this: ambiguous

  bool IsValid(std::string* error) const;
};

struct BoardPose {
  PoseStatus status = PoseStatus::kFailed;
  std::string message;      // why, when status is not ok
  bool has_pose = false;    // a pose was computed (ok, high_rms, ambiguous)
  Pose camera_from_target;  // p_in_camera = position + rotation · p_in_target; target unit
  // Covariance of (δ [rad], ε [target unit]) as defined above.
  Eigen::Matrix<double, 6, 6> covariance_local = Eigen::Matrix<double, 6, 6>::Zero();
  // Covariance of [x, y, z, q1, q2, q3] (target unit, degrees; Euler xyz).
  Eigen::Matrix<double, 6, 6> covariance_vector = Eigen::Matrix<double, 6, 6>::Zero();
  double rms_px = 0;              // reprojection RMS: sqrt(Σ |r_i|² / corners), pixels
  double variance_factor = 0;     // s² above
  double alternative_rms_px = 0;  // the other IPPE solution's, after refinement
  int num_tags = 0;
  int num_corners = 0;
};

BoardPose EstimateBoardPose(const Camera& camera, const BoardObservation& observation, const BoardPoseOptions& options);

// Pixel residuals (projected − observed), 2 per corner, of a pose.
Eigen::VectorXd ReprojectionResiduals(const Camera& camera, const BoardObservation& observation,
                                      const Pose& camera_from_target);

// Exp(δ) for a rotation vector δ, and its inverse (angle in [0, π]).
Eigen::Matrix3d RotationExp(const Eigen::Vector3d& delta);
Eigen::Vector3d RotationLog(const Eigen::Matrix3d& rotation);

}  // namespace hexcal

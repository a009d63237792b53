// The two residuals of the calibration from pixels (pixel_calibration.h), as
// Ceres functors for automatic differentiation: the leg reading's
// (core/leg_reading_residual.h, shared with the calibration from points) and
// the tag corners'. A platform pose block is [ω (angle-axis of R, radians),
// t (robot unit)] of base_from_platform.
#pragma once

#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "core/leg_reading_residual.h"
#include "core/pose.h"
#include "vision/camera.h"
#include "vision/pixel_projection.h"

namespace hexcal {

// The whitened reprojection error of one tag's 4 corners; blocks: pose (6),
// focal scale φ (1), principal point (2), target scale s (1).
struct TagCornersResidual {
  int image = 0;                             // the image's index (bookkeeping)
  int tag_id = 0;                            // the target's id of the tag (bookkeeping)
  const Camera* camera = nullptr;            // distortion and the file's fx, fy
  std::array<Eigen::Vector3d, 4> corners;    // target frame, robot unit
  Eigen::Matrix<double, 8, 1> observed;      // u0, v0, ..., u3, v3
  Eigen::Matrix<double, 8, 8> whitening;     // W with Wᵀ W = C⁻¹, C the corners' covariance
  Eigen::Matrix3d camera_from_base_rotation;
  Eigen::Vector3d camera_from_base_translation;
  Pose platform_from_target;

  template <typename T>
  bool operator()(const T* pose, const T* focal, const T* principal, const T* scale, T* residual) const {
    Eigen::Matrix<T, 8, 1> error;
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d in_platform_unit = platform_from_target.rotation * corners[c];
      T in_platform[3], in_base[3];
      for (int k = 0; k < 3; ++k) in_platform[k] = scale[0] * T(in_platform_unit[k]) + T(platform_from_target.position[k]);
      ceres::AngleAxisRotatePoint(pose, in_platform, in_base);
      T in_camera[3];
      for (int r = 0; r < 3; ++r) {
        in_camera[r] = T(camera_from_base_translation[r]);
        for (int k = 0; k < 3; ++k) in_camera[r] += T(camera_from_base_rotation(r, k)) * (in_base[k] + pose[3 + k]);
      }
      if (!(in_camera[2] > T(0))) return false;
      T uv[2];
      ProjectToPixel(*camera, focal[0] * T(camera->fx), focal[0] * T(camera->fy), principal[0], principal[1],
                     in_camera, uv);
      error[2 * c] = uv[0] - T(observed[2 * c]);
      error[2 * c + 1] = uv[1] - T(observed[2 * c + 1]);
    }
    Eigen::Map<Eigen::Matrix<T, 8, 1>> whitened(residual);
    whitened = whitening.cast<T>() * error;
    return true;
  }
};

}  // namespace hexcal

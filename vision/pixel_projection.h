// The camera model of camera.h written once more as a template, so that Ceres
// can differentiate a pixel through it (automatic differentiation): the
// calibration from pixels (pixel_calibration.h) estimates the focal length and
// the principal point while the distortion coefficients stay those of the
// camera file. Same equations as Camera::Distort and Camera::Project
// (checked against them in pixel_calibration_test.cc).
//
//   T uv[2];
//   ProjectToPixel(camera, fx, fy, cx, cy, p_in_camera, uv);
#pragma once

#include <ceres/jet.h>

#include <cmath>

#include "vision/camera.h"

namespace hexcal {

// Distorted normalised coordinates of undistorted (x, y), camera.h's models.
template <typename T>
void DistortNormalised(const Camera& camera, const T& x, const T& y, T* xd, T* yd) {
  using std::atan;
  using std::sqrt;
  const std::array<double, 8>& k = camera.distortion;
  const T r2 = x * x + y * y;
  if (camera.model == CameraModel::kPinholeEqui) {
    if (r2 < T(1e-24)) {
      *xd = x, *yd = y;
      return;
    }
    const T r = sqrt(r2);
    const T theta = atan(r);
    const T t2 = theta * theta;
    const T theta_d = theta * (T(1) + t2 * (T(k[0]) + t2 * (T(k[1]) + t2 * (T(k[2]) + t2 * T(k[3])))));
    *xd = x * theta_d / r, *yd = y * theta_d / r;
    return;
  }
  T radial = T(1) + r2 * (T(k[0]) + r2 * (T(k[1]) + r2 * T(k[4])));
  if (camera.model == CameraModel::kRational) radial /= T(1) + r2 * (T(k[5]) + r2 * (T(k[6]) + r2 * T(k[7])));
  const double p1 = k[2], p2 = k[3];
  *xd = x * radial + T(2 * p1) * x * y + T(p2) * (r2 + T(2) * x * x);
  *yd = y * radial + T(p1) * (r2 + T(2) * y * y) + T(2 * p2) * x * y;
}

// The pixel of a point in the camera frame (z > 0) with the given focal
// lengths and principal point and the camera's distortion.
template <typename T>
void ProjectToPixel(const Camera& camera, const T& fx, const T& fy, const T& cx, const T& cy, const T* p_in_camera,
                    T* uv) {
  T xd, yd;
  DistortNormalised(camera, p_in_camera[0] / p_in_camera[2], p_in_camera[1] / p_in_camera[2], &xd, &yd);
  uv[0] = fx * xd + cx;
  uv[1] = fy * yd + cy;
}

}  // namespace hexcal

// The leg reading's residual of the joint fits — the calibration from pixels
// (vision/pixel_calibration.h) and from points (core/point_calibration.h) —
// as a Ceres functor for automatic differentiation. A platform pose block is
// [ω (angle-axis of R, radians), t (robot unit)] of base_from_platform.
// Also the pieces both fits share: the pose block (PoseBlock, PoseOfBlock)
// and the solver's stopping rule (SetJointFitLimits).
// Internal: includes Ceres, which hexcal_core and hexcal_vision link privately.
#pragma once

#include <ceres/rotation.h>
#include <ceres/solver.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/pose.h"

namespace hexcal {

// A pose as the joint fits' block [ω, t] and back.
inline Vector6d PoseBlock(const Pose& pose) {
  Vector6d block;
  ceres::RotationMatrixToAngleAxis(pose.rotation.data(), block.data());
  block.tail<3>() = pose.position;
  return block;
}

inline Pose PoseOfBlock(const Vector6d& block) {
  Pose pose;
  ceres::AngleAxisToRotationMatrix(block.data(), pose.rotation.data());
  pose.position = block.tail<3>();
  return pose;
}

// The joint fits' stopping rule and threads (`num_threads` 0: every core).
inline void SetJointFitLimits(int max_iterations, int num_threads, ceres::Solver::Options* solver) {
  solver->max_num_iterations = max_iterations;
  solver->function_tolerance = 1e-12;
  solver->parameter_tolerance = 1e-12;
  solver->gradient_tolerance = 1e-14;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  solver->num_threads = num_threads > 0 ? num_threads : cores;
}

// (|A b − a| − (l + L)) / σ_L for one leg reading; blocks: leg [a, b, l] (7), pose (6).
struct LegReadingResidual {
  double reading = 0;  // L_ij, robot unit
  double sigma = 1;    // σ_L, robot unit

  template <typename T>
  bool operator()(const T* leg, const T* pose, T* residual) const {
    T b_in_base[3];
    ceres::AngleAxisRotatePoint(pose, leg + 3, b_in_base);
    T d2 = T(0);
    for (int k = 0; k < 3; ++k) {
      const T d = b_in_base[k] + pose[3 + k] - leg[k];
      d2 += d * d;
    }
    using std::sqrt;
    residual[0] = (sqrt(d2) - (leg[6] + T(reading))) / T(sigma);
    return true;
  }
};

}  // namespace hexcal

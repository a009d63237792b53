// Local forward kinematics: the pose whose inverse kinematics gives the
// readings, found by damped Gauss-Newton (Levenberg-Marquardt) from a start
// pose. Converges to the assembly mode nearest the start: use it for tracking
// a moving robot and for validation against a measured pose. For every
// assembly mode use ForwardKinematicsAll (fk_homotopy.h).
//
//   StatusOr<Pose> pose = ForwardKinematicsLocal(robot, readings, measured_pose);
#pragma once

#include "core/inverse_kinematics.h"
#include "core/status.h"

namespace hexcal {

struct LocalFkOptions {
  int max_iterations = 100;
  // Converged when every |L_i(pose) - L_i| is below tolerance * (1 + |L_i + l_i|).
  double tolerance = 1e-13;
  // A solution where the Jacobian's σ_min/σ_max (rotation columns divided by
  // the platform radius, so unit-free) is below this is a parallel
  // singularity: the readings do not determine the pose, an error.
  double min_condition_ratio = 1e-9;
  // Return a converged singular pose (with its condition_ratio) instead of the
  // error: for the end-game of ForwardKinematicsAll, which reports it as such.
  bool accept_singular = false;
};

struct LocalFkResult {
  Pose pose;
  int iterations = 0;
  double max_residual = 0;     // max |L_i(pose) - L_i|, robot unit
  double condition_ratio = 0;  // σ_min/σ_max of the scaled Jacobian at the pose (see LocalFkOptions)
};

// Fails (with the reason) when it does not converge, e.g. for readings that no
// pose can reach or a start at a singularity, and when it converges to a
// singular pose (min_condition_ratio), never with a NaN pose.
StatusOr<LocalFkResult> ForwardKinematicsLocal(const Robot& robot, const LegReadings& readings, const Pose& start,
                                               const LocalFkOptions& options = {});

// Applies a small motion [dP, theta] to a pose: P += dP, R <- exp([theta]x) R.
Pose ApplyIncrement(const Pose& pose, const Vector6d& increment);

}  // namespace hexcal

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
};

struct LocalFkResult {
  Pose pose;
  int iterations = 0;
  double max_residual = 0;  // max |L_i(pose) - L_i|, robot unit
};

// Fails (with the reason) when it does not converge, e.g. for readings that no
// pose can reach or a start at a singularity.
StatusOr<LocalFkResult> ForwardKinematicsLocal(const Robot& robot, const LegReadings& readings, const Pose& start,
                                               const LocalFkOptions& options = {});

// Applies a small motion [dP, theta] to a pose: P += dP, R <- exp([theta]x) R.
Pose ApplyIncrement(const Pose& pose, const Vector6d& increment);

}  // namespace hexcal

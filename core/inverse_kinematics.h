// Inverse kinematics of the 6-6 platform (paper eq. 3):
//   L_i = |P + R b_i - a_i| - l_i
//
//   LegReadings readings = InverseKinematics(robot, pose);
#pragma once

#include <Eigen/Core>

#include "core/pose.h"
#include "core/robot.h"

namespace hexcal {

using LegReadings = Eigen::Matrix<double, kNumLegs, 1>;

// v_i = P + R b_i - a_i, the leg from its base joint to its platform joint, in the base frame.
inline Eigen::Vector3d LegVector(const Leg& leg, const Pose& pose) {
  return pose.position + pose.rotation * leg.b_in_platform - leg.a_in_base;
}

// The six sensor readings L_i at a pose.
LegReadings InverseKinematics(const Robot& robot, const Pose& pose);

// The inverse-kinematics Jacobian: d L / d [P, theta] where theta is a small
// rotation applied on the left (R <- exp([theta]x) R). Row i = [u_i, (R b_i) x u_i],
// u_i the unit leg vector. Singular at the platform's parallel singularities.
Eigen::Matrix<double, kNumLegs, 6> InverseKinematicsJacobian(const Robot& robot, const Pose& pose);

}  // namespace hexcal

#include "core/inverse_kinematics.h"

namespace hexcal {

LegReadings InverseKinematics(const Robot& robot, const Pose& pose) {
  LegReadings readings;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    readings[i] = LegVector(leg, pose).norm() - leg.offset;
  }
  return readings;
}

Eigen::Matrix<double, kNumLegs, 6> InverseKinematicsJacobian(const Robot& robot, const Pose& pose) {
  Eigen::Matrix<double, kNumLegs, 6> jacobian;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const Eigen::Vector3d u = LegVector(leg, pose).normalized();
    const Eigen::Vector3d rb = pose.rotation * leg.b_in_platform;
    jacobian.row(i) << u.transpose(), rb.cross(u).transpose();
  }
  return jacobian;
}

}  // namespace hexcal

#include "core/identification.h"

namespace hexcal {

double ImplicitResidual(const Leg& leg, const Pose& pose, double reading) {
  const double length = reading + leg.offset;
  return LegVector(leg, pose).squaredNorm() - length * length;
}

JacobianRow ImplicitJacobianRow(const Leg& leg, const Pose& pose, double reading) {
  const Eigen::Vector3d v = LegVector(leg, pose);
  JacobianRow row;
  row << -2 * v.transpose(), 2 * (pose.rotation.transpose() * v).transpose(), -2 * (reading + leg.offset);
  return row;
}

JacobianRow NominalJacobianRow(const Leg& leg, const Pose& pose) {
  const Eigen::Vector3d v = LegVector(leg, pose);
  JacobianRow row;
  row << -2 * v.transpose(), 2 * (pose.rotation.transpose() * v).transpose(), -2 * v.norm();
  return row;
}

void InformationBlocks::AddPose(const Robot& robot, const Pose& pose, double weight) {
  for (int i = 0; i < kNumLegs; ++i) {
    const JacobianRow row = NominalJacobianRow(robot.legs[i], pose);
    blocks[i].noalias() += weight * row.transpose() * row;
  }
  ++num_poses;
}

void InformationBlocks::RemovePose(const Robot& robot, const Pose& pose) {
  AddPose(robot, pose, -1.0);
  num_poses -= 2;
}

InformationBlocks ComputeInformation(const Robot& robot, const std::vector<Pose>& poses) {
  InformationBlocks info;
  for (const Pose& pose : poses) info.AddPose(robot, pose);
  return info;
}

}  // namespace hexcal

// The implicit calibration model (paper section 5.2) and its identification
// Jacobian.
//
//   F_ij = |P_j + R_j b_i - a_i|² - (L_ij + l_i)²                      (eq. 4)
//   dF_ij / d(a_i, b_i, l_i) = [-2 v, 2 R_jᵀ v, -2 (L_ij + l_i)],
//   v = P_j + R_j b_i - a_i                                             (eq. 5 with its factor 2)
//
// Each F_ij depends only on leg i's 7 parameters, so the identification
// Jacobian J_P is block-diagonal (eq. 6) and everything is kept per leg as a
// 7x7 information block M_i = Σ_j row_ijᵀ row_ij.
//
//   InformationBlocks info = ComputeInformation(robot, poses);
//   ObservabilityIndices o = ComputeIndices(info);   // observability.h
#pragma once

#include <vector>

#include "core/inverse_kinematics.h"

namespace hexcal {

using JacobianRow = Eigen::Matrix<double, 1, kParamsPerLeg>;
using InfoBlock = Eigen::Matrix<double, kParamsPerLeg, kParamsPerLeg>;

// F_ij for leg i at a pose with reading L (eq. 4).
double ImplicitResidual(const Leg& leg, const Pose& pose, double reading);
// dF_ij/d(a_i, b_i, l_i) (eq. 5, with the factor 2).
JacobianRow ImplicitJacobianRow(const Leg& leg, const Pose& pose, double reading);
// The row at the reading the nominal model predicts (L + l = |v|), as the planner uses it.
JacobianRow NominalJacobianRow(const Leg& leg, const Pose& pose);

struct InformationBlocks {
  std::array<InfoBlock, kNumLegs> blocks;  // M_i = J_Piᵀ J_Pi
  int num_poses = 0;

  InformationBlocks() {
    for (InfoBlock& b : blocks) b.setZero();
  }
  void AddPose(const Robot& robot, const Pose& pose, double weight = 1.0);
  // Removing is adding with weight -1; the pose count follows the sign.
  void RemovePose(const Robot& robot, const Pose& pose);
};

InformationBlocks ComputeInformation(const Robot& robot, const std::vector<Pose>& poses);

}  // namespace hexcal

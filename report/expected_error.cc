#include "report/expected_error.h"

#include <Eigen/LU>
#include <cmath>

#include "core/inverse_kinematics.h"

namespace hexcal::workflow {
namespace {

// Squared expectations (variances summed over the three axes).
ExpectedPoseError SquaredExpectation(const Robot& robot, const Pose& pose, const NoiseModel& noise) {
  const double sigma_p = noise.PositionStdDev(), sigma_q = noise.AngleStdDevRad(), sigma_l = noise.LegStdDev();
  double position = 3 * sigma_p * sigma_p, rotation = 3 * sigma_q * sigma_q;
  const Eigen::Matrix<double, kNumLegs, 6> jacobian = InverseKinematicsJacobian(robot, pose);
  const Eigen::FullPivLU<Matrix6d> lu(jacobian.transpose() * jacobian);
  if (lu.isInvertible()) {
    const Matrix6d fk_covariance = sigma_l * sigma_l * lu.inverse();
    position += fk_covariance.topLeftCorner<3, 3>().trace();
    rotation += fk_covariance.bottomRightCorner<3, 3>().trace();
  }
  return {position, RadToDeg(RadToDeg(rotation))};  // rad² to deg²
}

}  // namespace

ExpectedPoseError ExpectedFkError(const Robot& robot, const Pose& pose, const NoiseModel& noise) {
  const ExpectedPoseError squared = SquaredExpectation(robot, pose, noise);
  return {std::sqrt(squared.position_rms), std::sqrt(squared.orientation_rms_deg)};
}

ExpectedPoseError ExpectedFkError(const Robot& robot, const std::vector<Pose>& poses, const NoiseModel& noise) {
  if (poses.empty()) return {};
  ExpectedPoseError sum;
  for (const Pose& pose : poses) {
    const ExpectedPoseError squared = SquaredExpectation(robot, pose, noise);
    sum.position_rms += squared.position_rms;
    sum.orientation_rms_deg += squared.orientation_rms_deg;
  }
  const double n = static_cast<double>(poses.size());
  return {std::sqrt(sum.position_rms / n), std::sqrt(sum.orientation_rms_deg / n)};
}

}  // namespace hexcal::workflow

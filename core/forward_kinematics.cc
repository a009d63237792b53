#include "core/forward_kinematics.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace hexcal {
namespace {

LegReadings Residual(const Robot& robot, const LegReadings& readings, const Pose& pose) {
  return InverseKinematics(robot, pose) - readings;
}

// σ_min/σ_max of dL/d[P, theta] with the theta columns divided by the
// platform radius: position and rotation columns then share a unit.
double ConditionRatio(const Robot& robot, const Pose& pose) {
  double radius = 0;
  for (const Leg& leg : robot.legs) radius = std::max(radius, leg.b_in_platform.norm());
  Eigen::Matrix<double, kNumLegs, 6> j = InverseKinematicsJacobian(robot, pose);
  if (radius > 0) j.rightCols<3>() /= radius;
  const Eigen::JacobiSVD<Eigen::Matrix<double, kNumLegs, 6>> svd(j);
  const Vector6d sigma = svd.singularValues();
  if (!sigma.allFinite() || !(sigma[0] > 0)) return 0;
  return sigma[5] / sigma[0];
}

}  // namespace

Pose ApplyIncrement(const Pose& pose, const Vector6d& increment) {
  Pose out;
  out.position = pose.position + increment.head<3>();
  const Eigen::Vector3d theta = increment.tail<3>();
  const double angle = theta.norm();
  const Eigen::Matrix3d delta =
      angle > 0 ? Eigen::AngleAxisd(angle, theta / angle).matrix() : Eigen::Matrix3d::Identity();
  out.rotation = delta * pose.rotation;
  return out;
}

StatusOr<LocalFkResult> ForwardKinematicsLocal(const Robot& robot, const LegReadings& readings, const Pose& start,
                                               const LocalFkOptions& options) {
  if (!readings.allFinite()) return Status::BadInput("forward kinematics: leg readings are not finite");
  double scale = 0;
  for (int i = 0; i < kNumLegs; ++i) scale = std::max(scale, std::abs(readings[i] + robot.legs[i].offset));
  const double tolerance = options.tolerance * (1 + scale);

  const auto singularity = [&](double ratio) {
    std::ostringstream message;
    message << "forward kinematics: the pose is at a singularity (Jacobian condition ratio " << ratio << " < "
            << options.min_condition_ratio << "): these readings do not determine the pose";
    return Status::Failed(message.str());
  };
  // Converged: a pose, unless it is a singular one.
  const auto solution = [&](const Pose& pose, int iterations, double max_residual) -> StatusOr<LocalFkResult> {
    const double ratio = ConditionRatio(robot, pose);
    if (!pose.position.allFinite() || !pose.rotation.allFinite()) return singularity(ratio);
    if (!options.accept_singular && !(ratio >= options.min_condition_ratio)) {
      return singularity(ratio);
    }
    return LocalFkResult{pose, iterations, max_residual, ratio};
  };
  Pose pose = start;
  LegReadings r = Residual(robot, readings, pose);
  double cost = r.squaredNorm();
  double lambda = 1e-6;
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    if (r.cwiseAbs().maxCoeff() <= tolerance) return solution(pose, iteration - 1, r.cwiseAbs().maxCoeff());
    const Eigen::Matrix<double, 6, 6> j = InverseKinematicsJacobian(robot, pose);
    const Eigen::Matrix<double, 6, 6> jtj = j.transpose() * j;
    const Vector6d jtr = j.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 30 && !improved; ++attempt) {
      Eigen::Matrix<double, 6, 6> damped = jtj;
      damped.diagonal() += lambda * (jtj.diagonal().array() + 1e-12).matrix();
      const Vector6d step = damped.ldlt().solve(-jtr);
      const Pose candidate = ApplyIncrement(pose, step);
      const LegReadings r_new = Residual(robot, readings, candidate);
      if (r_new.allFinite() && r_new.squaredNorm() < cost) {
        pose = candidate;
        r = r_new;
        cost = r.squaredNorm();
        lambda = std::max(lambda * 0.1, 1e-12);
        improved = true;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  const double max_residual = r.cwiseAbs().maxCoeff();
  if (max_residual <= tolerance * 1e3) return solution(pose, options.max_iterations, max_residual);
  // Near a singularity the steps stall: say so rather than blame the readings.
  if (const double ratio = ConditionRatio(robot, pose); !(ratio >= options.min_condition_ratio)) {
    return singularity(ratio);
  }
  std::ostringstream message;
  message << "forward kinematics did not converge: a leg length is still off by " << max_residual << " "
          << LengthUnitName(robot.length_unit) << " (readings out of reach, or a start pose too far from a solution)";
  return Status::Failed(message.str());
}

}  // namespace hexcal

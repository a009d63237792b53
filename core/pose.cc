#include "core/pose.h"

#include <algorithm>
#include <cmath>

namespace hexcal {
namespace {

Eigen::Matrix3d Rx(double q) { return Eigen::AngleAxisd(q, Eigen::Vector3d::UnitX()).matrix(); }
Eigen::Matrix3d Ry(double q) { return Eigen::AngleAxisd(q, Eigen::Vector3d::UnitY()).matrix(); }
Eigen::Matrix3d Rz(double q) { return Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()).matrix(); }

}  // namespace

std::optional<EulerConvention> ParseEulerConvention(const std::string& text) {
  if (text == "xyz") return EulerConvention::kXYZ;
  if (text == "zyx") return EulerConvention::kZYX;
  return std::nullopt;
}

const char* EulerConventionName(EulerConvention convention) {
  return convention == EulerConvention::kXYZ ? "xyz" : "zyx";
}

Eigen::Matrix3d RotationFromEuler(const Eigen::Vector3d& q, EulerConvention convention) {
  if (convention == EulerConvention::kXYZ) return Rz(q[2]) * Ry(q[1]) * Rx(q[0]);
  return Rx(q[2]) * Ry(q[1]) * Rz(q[0]);
}

Eigen::Vector3d EulerFromRotation(const Eigen::Matrix3d& r, EulerConvention convention) {
  if (convention == EulerConvention::kXYZ) {
    // R = Rz(c) Ry(b) Rx(a): r20 = -sin b, r21 = cos b sin a, r22 = cos b cos a,
    // r10 = sin c cos b, r00 = cos c cos b.
    const double b = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
    const double a = std::atan2(r(2, 1), r(2, 2));
    const double c = std::atan2(r(1, 0), r(0, 0));
    return {a, b, c};
  }
  // R = Rx(c) Ry(b) Rz(a): r02 = sin b, r01 = -cos b sin a, r00 = cos b cos a,
  // r12 = -sin c cos b, r22 = cos c cos b.
  const double b = std::asin(std::clamp(r(0, 2), -1.0, 1.0));
  const double a = std::atan2(-r(0, 1), r(0, 0));
  const double c = std::atan2(-r(1, 2), r(2, 2));
  return {a, b, c};
}

Pose PoseFromVector(const Vector6d& v, EulerConvention convention) {
  Pose pose;
  pose.position = v.head<3>();
  pose.rotation = RotationFromEuler(Eigen::Vector3d(DegToRad(v[3]), DegToRad(v[4]), DegToRad(v[5])), convention);
  return pose;
}

Vector6d VectorFromPose(const Pose& pose, EulerConvention convention) {
  const Eigen::Vector3d q = EulerFromRotation(pose.rotation, convention);
  Vector6d v;
  v << pose.position, RadToDeg(q[0]), RadToDeg(q[1]), RadToDeg(q[2]);
  return v;
}

double RotationDistance(const Eigen::Matrix3d& r1, const Eigen::Matrix3d& r2) {
  return Eigen::AngleAxisd(r1.transpose() * r2).angle();
}

}  // namespace hexcal

// Platform poses: base_from_platform as a position and a rotation matrix, and
// their 6-vector form [x, y, z, q1, q2, q3] used in every file.
//
// Conventions (docs/conventions.md): lengths in the robot file's unit, angles
// in degrees in the 6-vector, radians everywhere inside the code.
//   euler: xyz  ->  R = Rz(q3) * Ry(q2) * Rx(q1)   (the paper's convention)
//   euler: zyx  ->  R = Rx(q3) * Ry(q2) * Rz(q1)
//
// Rigid transforms compose as their names read (a_from_c = a_from_b · b_from_c),
// and the one chain of the camera registration is written here once:
// X = base_from_camera, Y = platform_from_target, B = camera_from_target,
// A = base_from_platform, with A · Y = X · B.
//
//   Pose pose = PoseFromVector({0, 0, 53, 5, 0, 0}, EulerConvention::kXYZ);
//   Eigen::Vector3d b_in_base = pose * b_in_platform;
//   Pose camera_from_target = CameraFromTarget(base_from_camera, pose, platform_from_target);
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace hexcal {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

enum class EulerConvention { kXYZ, kZYX };

std::optional<EulerConvention> ParseEulerConvention(const std::string& text);
const char* EulerConventionName(EulerConvention convention);

struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // platform origin in base
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();

  Eigen::Vector3d operator*(const Eigen::Vector3d& p_in_platform) const { return position + rotation * p_in_platform; }
};

// Rotation from Euler angles in radians.
Eigen::Matrix3d RotationFromEuler(const Eigen::Vector3d& q_rad, EulerConvention convention);
// Euler angles in radians, q2 in [-pi/2, pi/2]; continuous away from gimbal lock.
Eigen::Vector3d EulerFromRotation(const Eigen::Matrix3d& rotation, EulerConvention convention);

// [x, y, z, q1, q2, q3] with angles in degrees.
Pose PoseFromVector(const Vector6d& xyz_q_deg, EulerConvention convention);
Vector6d VectorFromPose(const Pose& pose, EulerConvention convention);

// a_from_c = a_from_b · b_from_c.
Pose Compose(const Pose& a_from_b, const Pose& b_from_c);
// b_from_a = a_from_b⁻¹.
Pose Inverse(const Pose& a_from_b);
// The platform in the base frame from the camera's view of the target: X · B · Y⁻¹.
Pose BaseFromPlatform(const Pose& base_from_camera, const Pose& camera_from_target, const Pose& platform_from_target);
// Its inverse in B: what the camera sees of the target at a platform pose, X⁻¹ · A · Y.
Pose CameraFromTarget(const Pose& base_from_camera, const Pose& base_from_platform, const Pose& platform_from_target);

// Rotation angle between two rotations, radians.
double RotationDistance(const Eigen::Matrix3d& r1, const Eigen::Matrix3d& r2);

constexpr double kPi = 3.14159265358979323846;
constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }

}  // namespace hexcal

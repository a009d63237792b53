#include "core/pose.h"

#include <algorithm>
#include <cmath>

namespace hexcal {
namespace {

// cos, sin and the diagonal 1 of an elementary rotation, as Eigen's AngleAxis
// writes them ((1 - cos) + cos: an ulp off 1 at times).
struct Elementary {
  double c, s, one;
};
Elementary ElementaryOf(double q) {
  const double c = std::cos(q), s = std::sin(q);
  return {c, s, (1 - c) + c};
}

// R = Rz(c) Ry(b) Rx(a) with the nonzero terms of the two 3 x 3 products only
// (a quarter of the time of multiplying AngleAxis matrices, which this is
// bit-for-bit: pose_test checks it; + 0.0 turns the -0 of a vanished term into
// the +0 the full product gives).
Eigen::Matrix3d RzRyRx(const Elementary& a, const Elementary& b, const Elementary& c) {
  const double t00 = c.c * b.c, t01 = -c.s * b.one, t02 = c.c * b.s;  // T = Rz Ry, t21 = 0
  const double t10 = c.s * b.c, t11 = c.c * b.one, t12 = c.s * b.s;
  const double t20 = c.one * -b.s, t22 = c.one * b.c;
  Eigen::Matrix3d r;
  // clang-format off
  r << t00 * a.one, t01 * a.c + t02 * a.s, t01 * -a.s + t02 * a.c,
       t10 * a.one, t11 * a.c + t12 * a.s, t11 * -a.s + t12 * a.c,
       t20 * a.one, t22 * a.s,             t22 * a.c;
  // clang-format on
  return r.array() + 0.0;
}

// R = Rx(c) Ry(b) Rz(a), likewise.
Eigen::Matrix3d RxRyRz(const Elementary& a, const Elementary& b, const Elementary& c) {
  const double t00 = c.one * b.c, t02 = c.one * b.s;  // T = Rx Ry, t01 = 0
  const double t10 = -c.s * -b.s, t11 = c.c * b.one, t12 = -c.s * b.c;
  const double t20 = c.c * -b.s, t21 = c.s * b.one, t22 = c.c * b.c;
  Eigen::Matrix3d r;
  // clang-format off
  r << t00 * a.c,             t00 * -a.s,             t02 * a.one,
       t10 * a.c + t11 * a.s, t10 * -a.s + t11 * a.c, t12 * a.one,
       t20 * a.c + t21 * a.s, t20 * -a.s + t21 * a.c, t22 * a.one;
  // clang-format on
  return r.array() + 0.0;
}

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
  const Elementary a = ElementaryOf(q[0]), b = ElementaryOf(q[1]), c = ElementaryOf(q[2]);
  return convention == EulerConvention::kXYZ ? RzRyRx(a, b, c) : RxRyRz(a, b, c);
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

Pose Compose(const Pose& a_from_b, const Pose& b_from_c) {
  Pose a_from_c;
  a_from_c.rotation = a_from_b.rotation * b_from_c.rotation;
  a_from_c.position = a_from_b.rotation * b_from_c.position + a_from_b.position;
  return a_from_c;
}

Pose Inverse(const Pose& a_from_b) {
  Pose b_from_a;
  b_from_a.rotation = a_from_b.rotation.transpose();
  b_from_a.position = -(b_from_a.rotation * a_from_b.position);
  return b_from_a;
}

Pose BaseFromPlatform(const Pose& base_from_camera, const Pose& camera_from_target, const Pose& platform_from_target) {
  return Compose(Compose(base_from_camera, camera_from_target), Inverse(platform_from_target));
}

Pose CameraFromTarget(const Pose& base_from_camera, const Pose& base_from_platform, const Pose& platform_from_target) {
  return Compose(Compose(Inverse(base_from_camera), base_from_platform), platform_from_target);
}

}  // namespace hexcal

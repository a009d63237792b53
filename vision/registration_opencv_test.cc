// core/registration.h against OpenCV's robot-world hand-eye calibration
// (cv::calibrateRobotWorldHandEye, Shah's method) on the same poses. OpenCV's
// frames map onto hexcal's as: its camera = our camera, its gripper = our base,
// its robot base = our platform, its world = our target, so its inputs are
// R_world2cam = camera_from_target, R_base2gripper = base_from_platform and its
// outputs gripper2cam = base_from_camera⁻¹, base2world = platform_from_target⁻¹.
#include <gtest/gtest.h>

#include <Eigen/Core>  // before opencv2/core/eigen.hpp
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "core/registration.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Uniform;

Pose RandomPose(double position, double angle_deg) {
  Vector6d v;
  for (int k = 0; k < 6; ++k) v[k] = Uniform(-1, 1) * (k < 3 ? position : angle_deg);
  return PoseFromVector(v, EulerConvention::kXYZ);
}

cv::Mat ToCv(const Eigen::Matrix3d& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}
cv::Mat ToCv(const Eigen::Vector3d& v) {
  cv::Mat out;
  cv::eigen2cv(v, out);
  return out;
}

TEST(RegistrationAgainstOpenCv, BothRecoverTheFramesFromExactPoses) {
  const Pose base_from_camera =
      PoseFromVector((Vector6d() << 4, -3, 120, 178, 3, 40).finished(), EulerConvention::kXYZ);
  const Pose platform_from_target =
      PoseFromVector((Vector6d() << 0.5, -1, 2, 2, -1, 25).finished(), EulerConvention::kXYZ);
  std::vector<Pose> robot_poses, camera_poses;
  std::vector<cv::Mat> r_world2cam, t_world2cam, r_base2gripper, t_base2gripper;
  for (int j = 0; j < 15; ++j) {
    Pose a = RandomPose(5, 20);
    a.position.z() += 53;
    const Pose b = Compose(Compose(Inverse(base_from_camera), a), platform_from_target);
    robot_poses.push_back(a);
    camera_poses.push_back(b);
    r_world2cam.push_back(ToCv(b.rotation));
    t_world2cam.push_back(ToCv(b.position));
    r_base2gripper.push_back(ToCv(a.rotation));
    t_base2gripper.push_back(ToCv(a.position));
  }
  StatusOr<Registration> ours = EstimateRegistration(robot_poses, camera_poses);
  ASSERT_TRUE(ours.ok()) << ours.status().message();

  cv::Mat r_base2world, t_base2world, r_gripper2cam, t_gripper2cam;
  cv::calibrateRobotWorldHandEye(r_world2cam, t_world2cam, r_base2gripper, t_base2gripper, r_base2world, t_base2world,
                                 r_gripper2cam, t_gripper2cam, cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH);
  Pose camera_from_base, target_from_platform;
  cv::cv2eigen(r_gripper2cam, camera_from_base.rotation);
  cv::cv2eigen(t_gripper2cam, camera_from_base.position);
  cv::cv2eigen(r_base2world, target_from_platform.rotation);
  cv::cv2eigen(t_base2world, target_from_platform.position);
  const Pose opencv_x = Inverse(camera_from_base), opencv_y = Inverse(target_from_platform);

  for (const Pose& x : {ours->base_from_camera, opencv_x}) {
    EXPECT_LT((x.position - base_from_camera.position).norm(), 1e-6);
    EXPECT_LT(RotationDistance(x.rotation, base_from_camera.rotation), 1e-8);
  }
  for (const Pose& y : {ours->platform_from_target, opencv_y}) {
    EXPECT_LT((y.position - platform_from_target.position).norm(), 1e-6);
    EXPECT_LT(RotationDistance(y.rotation, platform_from_target.rotation), 1e-8);
  }
}

}  // namespace
}  // namespace hexcal

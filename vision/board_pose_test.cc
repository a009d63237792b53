#include "vision/board_pose.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/test_support.h"
#include "vision/renderer.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TestRng;
using ::testing::HasSubstr;

// Exact projections of the given tags plus isotropic Gaussian noise.
BoardObservation Synthetic(const Camera& camera, const Target& target, const Pose& pose, const std::vector<int>& ids,
                           double sigma_px) {
  std::normal_distribution<double> noise(0, sigma_px);
  BoardObservation observation;
  for (int id : ids) {
    observation.tag_ids.push_back(id);
    for (const Eigen::Vector3d& p : target.TagCorners(id)) {
      observation.target_points.push_back(p);
      observation.image_points.push_back(camera.Project(pose * p) +
                                         Eigen::Vector2d(noise(TestRng()), noise(TestRng())));
    }
  }
  return observation;
}

std::vector<int> AllIds(const Target& target) {
  std::vector<int> ids(static_cast<size_t>(target.NumTags()));
  for (int i = 0; i < target.NumTags(); ++i) ids[static_cast<size_t>(i)] = target.first_id + i;
  return ids;
}

Eigen::Matrix<double, 6, 1> LocalError(const Pose& estimate, const Pose& truth) {
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = RotationLog(estimate.rotation * truth.rotation.transpose());
  e.tail<3>() = estimate.position - truth.position;
  return e;
}

double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The board poses found in views of the default target, and their errors.
struct RenderedPoses {
  std::vector<BoardPose> found;
  std::vector<double> translation_mm, rotation_deg;
};

// What `measure` does: each view rendered through `camera` at `poses` (the
// renderer's default noise), detected with the edge fit in its undistorted
// image, then posed. A view without a pose is a fatal failure.
void PoseRenderedViews(const Camera& camera, const std::vector<Pose>& poses, RenderedPoses* out) {
  const Target target = DefaultTarget();
  const Renderer renderer(camera, target, RenderOptions{});
  std::unique_ptr<TagDetector> detector =
      TagDetector::Create(DetectorOptions{}, std::make_shared<const IdealPixelMap>(camera)).value();
  for (size_t i = 0; i < poses.size(); ++i) {
    const RenderedView view = renderer.Render(poses[i], i);
    const BoardPose pose = EstimateBoardPose(camera, MatchToTarget(target, detector->Detect(view.image)), {});
    ASSERT_EQ(pose.status, PoseStatus::kOk) << pose.message;
    out->found.push_back(pose);
    out->translation_mm.push_back((pose.camera_from_target.position - poses[i].position).norm());
    out->rotation_deg.push_back(RadToDeg(RotationDistance(pose.camera_from_target.rotation, poses[i].rotation)));
  }
}

TEST(BoardPoseTest, RotationExpAndLogAreInverse) {
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d delta = Eigen::Vector3d::Random() * 1.5;
    EXPECT_TRUE(testing::MatrixNear(RotationLog(RotationExp(delta)), delta, 1e-12));
  }
  EXPECT_TRUE(testing::MatrixNear(RotationExp(Eigen::Vector3d::Zero()), Eigen::Matrix3d::Identity(), 0));
}

TEST(BoardPoseTest, CovarianceMatchesErrorsOfIsotropicCornerNoise) {
  const Camera camera = SimulatedCamera();
  const Target target = DefaultTarget();
  const std::vector<Pose> poses = RandomViewPoses(target, 200, 300, 800, 40, 30, 0.15, 3);
  double nees = 0;
  for (const Pose& truth : poses) {
    const BoardPose pose = EstimateBoardPose(camera, Synthetic(camera, target, truth, AllIds(target), 0.1), {});
    ASSERT_EQ(pose.status, PoseStatus::kOk) << pose.message;
    const Eigen::Matrix<double, 6, 1> e = LocalError(pose.camera_from_target, truth);
    nees += e.dot(pose.covariance_local.ldlt().solve(e));
    // The vector form shares the position block.
    EXPECT_TRUE(testing::MatrixNear(pose.covariance_vector.topLeftCorner<3, 3>(),
                                    pose.covariance_local.bottomRightCorner<3, 3>(), 1e-9));
    EXPECT_NEAR(pose.variance_factor, 0.01, 0.004);
  }
  // χ² with 6 degrees of freedom: mean 6, standard error of the mean of 200 about 0.25.
  EXPECT_NEAR(nees / poses.size(), 6, 1.0);
}

// OpenCV's PnP takes the rational coefficients; the fisheye is solved on
// undistorted corners: both find the pose wherever the board is in the image.
TEST(BoardPoseTest, EveryCameraModelFindsThePose) {
  Camera rational = SimulatedCamera();
  rational.model = CameraModel::kRational;
  rational.distortion = {0.4, -0.1, 0.0004, -0.0003, 0.02, 0.68, 0.02, 0.01};
  const Target target = DefaultTarget();
  for (const Camera& camera : {rational, SimulatedFisheyeCamera()}) {
    const double distance = camera.model == CameraModel::kPinholeEqui ? 250 : 500;
    for (const Pose& truth : RandomViewPoses(target, 30, distance, 2 * distance, 45, 30, 0.6, 5)) {
      const BoardPose pose = EstimateBoardPose(camera, Synthetic(camera, target, truth, AllIds(target), 0.1), {});
      ASSERT_EQ(pose.status, PoseStatus::kOk) << CameraModelName(camera.model) << ": " << pose.message;
      const Eigen::Matrix<double, 6, 1> e = LocalError(pose.camera_from_target, truth);
      EXPECT_LT(e.dot(pose.covariance_local.ldlt().solve(e)), 40) << CameraModelName(camera.model);
    }
  }
}

TEST(BoardPoseTest, StatusesSayWhy) {
  const Camera camera = SimulatedCamera();
  const Target target = DefaultTarget();
  const Pose truth = RandomViewPoses(target, 1, 500, 500, 20, 0, 0, 1)[0];
  BoardPose pose = EstimateBoardPose(camera, BoardObservation{}, {});
  EXPECT_EQ(pose.status, PoseStatus::kNoTarget);
  EXPECT_FALSE(pose.has_pose);
  pose = EstimateBoardPose(camera, Synthetic(camera, target, truth, {0, 1, 2}, 0.05), {});
  EXPECT_EQ(pose.status, PoseStatus::kTooFewTags);
  EXPECT_EQ(pose.message, "3 tags of the target found, 4 needed");
  pose = EstimateBoardPose(camera, Synthetic(camera, target, truth, AllIds(target), 3.0), {});
  EXPECT_EQ(pose.status, PoseStatus::kHighRms);
  EXPECT_TRUE(pose.has_pose);
  EXPECT_THAT(pose.message, HasSubstr("reprojection RMS"));
  // One small tag far away, seen square on: the two IPPE poses fit alike.
  BoardPoseOptions one_tag;
  one_tag.min_tags = 1;
  Pose far = truth;
  far.position = Eigen::Vector3d(0, 0, 3000) - far.rotation * Eigen::Vector3d(15, 15, 0);
  int ambiguous = 0;
  for (int trial = 0; trial < 10; ++trial) {
    pose = EstimateBoardPose(camera, Synthetic(camera, target, far, {0}, 0.3), one_tag);
    ambiguous += pose.status == PoseStatus::kAmbiguous;
  }
  EXPECT_GE(ambiguous, 5);
  EXPECT_STREQ(PoseStatusName(PoseStatus::kAmbiguous), "ambiguous");
}

// The acceptance figure: rendered images at 0.5 m under the
// renderer's default noise, median errors within 0.05 mm and 0.01°.
TEST(BoardPoseTest, RecoversRenderedPosesAtHalfAMetre) {
  const std::vector<Pose> poses = RandomViewPoses(DefaultTarget(), 12, 500, 500, 30, 30, 0.1, 2026);
  RenderedPoses r;
  ASSERT_NO_FATAL_FAILURE(PoseRenderedViews(SimulatedCamera(), poses, &r));
  double nees = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(r.found[i].num_tags, 36);
    const Eigen::Matrix<double, 6, 1> e = LocalError(r.found[i].camera_from_target, poses[i]);
    nees += e.dot(r.found[i].covariance_local.ldlt().solve(e));
  }
  EXPECT_LE(Median(r.translation_mm), 0.05);
  EXPECT_LE(Median(r.rotation_deg), 0.01);
  // Normalised errors: the reported covariance is neither far too small nor far too large.
  EXPECT_GT(nees / poses.size(), 1.5);
  EXPECT_LT(nees / poses.size(), 18);
  std::cout << "median translation error " << Median(r.translation_mm) << " mm, rotation " << Median(r.rotation_deg)
            << " deg, mean NEES " << nees / poses.size() << " (6 expected)\n";
}

// What `measure` does with a fisheye: detection with the edge fit in its
// undistorted image, then the pose; rendered views up to ~50° off the axis.
TEST(BoardPoseTest, RecoversRenderedPosesThroughAFisheye) {
  RenderedPoses r;
  ASSERT_NO_FATAL_FAILURE(PoseRenderedViews(SimulatedFisheyeCamera(),
                                            RandomViewPoses(DefaultTarget(), 8, 300, 300, 30, 30, 0.6, 2027), &r));
  std::cout << "fisheye: median translation error " << Median(r.translation_mm) << " mm, rotation "
            << Median(r.rotation_deg) << " deg\n";
  EXPECT_LE(Median(r.translation_mm), 0.05);
  EXPECT_LE(Median(r.rotation_deg), 0.01);
}

}  // namespace
}  // namespace hexcal

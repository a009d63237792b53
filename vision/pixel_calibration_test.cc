#include "vision/pixel_calibration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/inverse_kinematics.h"
#include "core/registration.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"
#include "vision/board_pose.h"
#include "vision/pixel_projection.h"

namespace hexcal {
namespace {

using testing::Accuracy;
using testing::AccuracyInRegisteredFrames;
using testing::PerturbedRobot;
using testing::Preset;
using testing::SpreadFeasiblePoses;

TEST(PixelProjection, MatchesTheCameraModelOfEveryDistortion) {
  Camera camera = SimulatedCamera();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (CameraModel model : {CameraModel::kRadTan, CameraModel::kRational, CameraModel::kPinholeEqui}) {
    camera.model = model;
    camera.distortion = {-0.2, 0.05, 0.001, -0.002, 0.01, 0.02, -0.01, 0.005};
    if (model == CameraModel::kPinholeEqui) camera.distortion = {0.05, -0.01, 0.002, -0.001, 0, 0, 0, 0};
    if (model == CameraModel::kRadTan) camera.distortion[5] = camera.distortion[6] = camera.distortion[7] = 0;
    for (int n = 0; n < 50; ++n) {
      const double p[3] = {u(rng), u(rng), 1.0 + u(rng)};
      double uv[2];
      ProjectToPixel(camera, camera.fx, camera.fy, camera.cx, camera.cy, p, uv);
      const Eigen::Vector2d expected = camera.Project(Eigen::Vector3d(p[0], p[1], p[2]));
      EXPECT_NEAR(uv[0], expected.x(), 1e-9) << CameraModelName(model);
      EXPECT_NEAR(uv[1], expected.y(), 1e-9) << CameraModelName(model);
    }
  }
}

// A virtual session: the true robot at random poses under a camera 70 cm
// above the platform, a 6 × 6 board of 3 cm tags (in mm) on the platform; the
// corners projected by the true camera with 0.1 px noise, the legs read with
// uniform noise of ±0.001 cm.
struct Scene {
  Robot nominal, truth;
  Camera true_camera;
  Pose base_from_camera, platform_from_target;
  std::vector<Pose> poses;
  std::vector<LegReadings> legs;
  std::vector<BoardObservation> seen;
};

BoardObservation Observe(const Scene& scene, const Pose& pose, double scale, std::mt19937_64* rng) {
  std::normal_distribution<double> pixel_noise(0, 0.1);
  const Pose camera_from_target = Compose(Inverse(scene.base_from_camera), Compose(pose, scene.platform_from_target));
  BoardObservation seen;
  for (int id = 0; id < 36; ++id) {
    const double x = 39.0 * (id % 6) - 112.5, y = 39.0 * (id / 6) - 112.5;  // mm, board centred
    const Eigen::Vector3d corners[4] = {{x, y, 0}, {x + 30, y, 0}, {x + 30, y + 30, 0}, {x, y + 30, 0}};
    std::vector<Eigen::Vector2d> pixels;
    for (const Eigen::Vector3d& c : corners) {
      const Eigen::Vector2d uv = scene.true_camera.Project(camera_from_target * (c * 0.1 * scale));
      if (uv.x() >= 0 && uv.y() >= 0 && uv.x() < scene.true_camera.width && uv.y() < scene.true_camera.height)
        pixels.push_back(uv + Eigen::Vector2d(pixel_noise(*rng), pixel_noise(*rng)));
    }
    if (pixels.size() < 4) continue;  // a tag partly outside the image is not detected
    seen.tag_ids.push_back(id);
    seen.target_points.insert(seen.target_points.end(), corners, corners + 4);
    seen.image_points.insert(seen.image_points.end(), pixels.begin(), pixels.end());
    seen.corner_covariances.push_back(Eigen::Matrix<double, 8, 8>::Identity() * 0.01);
  }
  return seen;
}

Scene MakeScene(int images, double target_scale, uint64_t seed) {
  Scene scene;
  scene.nominal = Preset("inria-left-hand");
  scene.truth = PerturbedRobot(scene.nominal, 0.05);
  scene.true_camera = SimulatedCamera();
  Vector6d camera;
  camera << 1.5, -2, 123, 180, 2, -4;
  scene.base_from_camera = PoseFromVector(camera, EulerConvention::kXYZ);
  Vector6d target;
  target << 0.3, -0.2, 0.5, 1, -2, 5;
  scene.platform_from_target = PoseFromVector(target, EulerConvention::kXYZ);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> leg_noise(-0.001, 0.001);
  for (const Vector6d& v : SpreadFeasiblePoses(scene.truth, images, seed)) {
    const Pose pose = scene.truth.PoseFromVector(v);
    LegReadings legs = InverseKinematics(scene.truth, pose);
    for (int i = 0; i < kNumLegs; ++i) legs[i] += leg_noise(rng);
    scene.poses.push_back(pose);
    scene.legs.push_back(legs);
    scene.seen.push_back(Observe(scene, pose, target_scale, &rng));
  }
  return scene;
}

// The two-stage calibration as calibrate --session runs it: a board pose per
// image (EstimateBoardPose with `camera`), registration with the nominal robot,
// the legs fitted to the poses weighted by their covariance.
CameraCalibrationResult TwoStage(const Scene& scene, const Camera& camera) {
  CameraCalibrationInput input;
  for (size_t j = 0; j < scene.poses.size(); ++j) {
    const BoardPose board = EstimateBoardPose(camera, scene.seen[j], BoardPoseOptions{});
    EXPECT_EQ(board.status, PoseStatus::kOk) << board.message;
    Pose camera_from_target = board.camera_from_target;
    camera_from_target.position *= 0.1;  // mm to cm
    Matrix6d covariance = board.covariance_vector;
    covariance.topRows<3>() *= 0.1;
    covariance.leftCols<3>() *= 0.1;
    input.camera_from_target.push_back(camera_from_target);
    input.camera_pose_covariance.push_back(covariance);
    input.legs.push_back(scene.legs[j]);
    input.fk_start.push_back(scene.poses[j]);
  }
  const NoiseModel noise;  // the paper's levels, as the scene's legs
  const RegistrationOptions registration = RegistrationOptionsFromNoise(noise);
  CalibrationOptions calibration;
  calibration.weighted = true;
  calibration.noise = noise;
  calibration.uncertainty_scale = UncertaintyScale::kAtLeastAPriori;
  StatusOr<CameraCalibrationResult> result = CalibrateFromCameraPoses(scene.nominal, input, registration, calibration);
  EXPECT_TRUE(result.ok()) << result.status().message();
  return result.ok() ? *result : CameraCalibrationResult{};
}

// The pixel fit's input as calibrate --session gives it: started from the
// two-stage calibration, in its registered frames.
PixelCalibrationInput InputOf(const Scene& scene, const Camera& camera, const CameraCalibrationResult& two_stage) {
  PixelCalibrationInput input{scene.nominal, two_stage.calibration.robot, camera, 0.1,
                              two_stage.registration.base_from_camera, two_stage.registration.platform_from_target, {}};
  for (size_t j = 0; j < scene.poses.size(); ++j) {
    PixelImage image;
    image.observation = scene.seen[j];
    image.legs = scene.legs[j];
    image.base_from_platform = two_stage.calibration.robot.PoseFromVector(two_stage.measurements[j].pose);
    input.images.push_back(image);
  }
  return input;
}

// The session's reading noise (±0.001 cm uniform) and the given camera and target estimates.
PixelCalibrationOptions Options(bool focal, bool target_scale) {
  PixelCalibrationOptions options;
  options.estimate_focal = focal;
  options.estimate_target_scale = target_scale;
  options.leg_sigma = 0.001 / std::sqrt(3.0);
  return options;
}

// The errors of the 42 parameters against the truth in the registered frames
// (the gauge, docs/session.md).
Accuracy AccuracyOf(const CalibrationResult& fit, const Scene& scene, const Registration& frames) {
  return AccuracyInRegisteredFrames(fit, scene.truth, scene.base_from_camera, scene.platform_from_target, frames);
}

TEST(CalibrateFromPixels, IsAtLeastAsAccurateAsTwoStageWithHonestSigmas) {
  const Scene scene = MakeScene(40, 1.0, 7);
  const CameraCalibrationResult two_stage = TwoStage(scene, scene.true_camera);
  StatusOr<PixelCalibrationResult> fit =
      CalibrateFromPixels(InputOf(scene, scene.true_camera, two_stage), Options(true, false));
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  const Accuracy pixels = AccuracyOf(fit->calibration, scene, two_stage.registration);
  const Accuracy poses = AccuracyOf(two_stage.calibration, scene, two_stage.registration);
  std::printf("true camera: pixels %.5f (%.3f within 3 sigma), two-stage %.5f (%.3f)\n", pixels.mean_error,
              pixels.within_3sigma, poses.mean_error, poses.within_3sigma);
  EXPECT_GE(pixels.within_3sigma, 0.95);
  EXPECT_LE(pixels.mean_error, poses.mean_error * 1.05);
  EXPECT_NEAR(fit->variance_factor, 1.0, 0.2);
  EXPECT_NEAR(fit->reprojection_rms_px, 0.1 * std::sqrt(2.0), 0.02);  // per corner, u and v
  ASSERT_EQ(fit->extras.size(), 2u);                                    // fx, fy
  // Every corner named with its image, tag and detected pixel; their scatter is the 0.1 px noise put in.
  ASSERT_EQ(fit->corner_residuals.size(), static_cast<size_t>(fit->corners));
  for (const CornerResidual& c : fit->corner_residuals) {
    const BoardObservation& seen = scene.seen[c.image];
    const size_t tag = std::find(seen.tag_ids.begin(), seen.tag_ids.end(), c.tag_id) - seen.tag_ids.begin();
    ASSERT_LT(tag, seen.tag_ids.size());
    ASSERT_EQ(c.observed, seen.image_points[4 * tag + c.corner]);
  }
  EXPECT_NEAR(RobustAxisSigma(fit->corner_residuals), 0.1, 0.005);
  EXPECT_NEAR(fit->extras[0].estimate, scene.true_camera.fx, 4 * fit->extras[0].sigma);
}

TEST(CalibrateFromPixels, EstimatesAFocalLengthErrorAway) {
  const Scene scene = MakeScene(40, 1.0, 11);
  Camera wrong = scene.true_camera;
  wrong.fx *= 1.005;
  wrong.fy *= 1.005;
  const CameraCalibrationResult two_stage = TwoStage(scene, wrong);
  StatusOr<PixelCalibrationResult> fit = CalibrateFromPixels(InputOf(scene, wrong, two_stage), Options(true, false));
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_NEAR(fit->camera.fx, scene.true_camera.fx, 4 * fit->extras[0].sigma);
  const Accuracy pixels = AccuracyOf(fit->calibration, scene, two_stage.registration);
  const Accuracy poses = AccuracyOf(two_stage.calibration, scene, two_stage.registration);
  std::printf("0.5 %% focal error: pixels %.5f (%.3f within 3 sigma), two-stage %.5f (%.3f)\n", pixels.mean_error,
              pixels.within_3sigma, poses.mean_error, poses.within_3sigma);
  EXPECT_GE(pixels.within_3sigma, 0.95);
  EXPECT_LE(pixels.mean_error, 0.5 * poses.mean_error);
}

TEST(CalibrateFromPixels, EstimatesTheTargetScale) {
  const Scene scene = MakeScene(40, 1.004, 5);
  const CameraCalibrationResult two_stage = TwoStage(scene, scene.true_camera);
  StatusOr<PixelCalibrationResult> fit =
      CalibrateFromPixels(InputOf(scene, scene.true_camera, two_stage), Options(true, true));
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_NEAR(fit->target_scale, 1.004, 4 * fit->extras.back().sigma);
  EXPECT_GE(AccuracyOf(fit->calibration, scene, two_stage.registration).within_3sigma, 0.95);
}

TEST(CalibrateFromPixels, RefusesTooFewImagesAndBadOptions) {
  const Scene scene = MakeScene(8, 1.0, 1);
  const CameraCalibrationResult two_stage = TwoStage(scene, scene.true_camera);
  PixelCalibrationInput few = InputOf(scene, scene.true_camera, two_stage);
  few.images.resize(5);
  StatusOr<PixelCalibrationResult> fit = CalibrateFromPixels(few, {});
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("at least 7"), std::string::npos);
  PixelCalibrationOptions no_noise = Options(true, false);
  no_noise.leg_sigma = 0;
  fit = CalibrateFromPixels(InputOf(scene, scene.true_camera, two_stage), no_noise);
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("leg_sigma"), std::string::npos);
}

TEST(CalibrateFromPixels, StopsWhenCancelled) {
  const Scene scene = MakeScene(10, 1.0, 2);
  std::atomic<bool> cancel{true};
  StatusOr<PixelCalibrationResult> fit = CalibrateFromPixels(
      InputOf(scene, scene.true_camera, TwoStage(scene, scene.true_camera)), {}, JobHooks{nullptr, &cancel});
  EXPECT_TRUE(fit.status().cancelled());
}

}  // namespace
}  // namespace hexcal

// Registration (A_j Y = X B_j) and calibration from camera poses against an
// independent truth made here: a perturbed robot, a camera above the platform
// and a target on it at known frames, camera poses computed from the true
// robot's poses. Exact data must give the frames and the gauge-moved true
// parameters back; noisy data must stay within the reported 3σ.
#include "core/registration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>

#include "core/candidates.h"
#include "core/inverse_kinematics.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::Preset;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

using ::hexcal::testing::PerturbedRobot;
using ::hexcal::testing::RandomFeasiblePoses;

// A camera 120 units above the base looking down (x right, y down, z forward),
// a little off-axis; a target 2 units above the platform origin, turned.
Pose TrueBaseFromCamera() {
  return PoseFromVector((Vector6d() << 4, -3, 120, 178, 3, 40).finished(), EulerConvention::kXYZ);
}
Pose TruePlatformFromTarget() {
  return PoseFromVector((Vector6d() << 0.5, -1, 2, 2, -1, 25).finished(), EulerConvention::kXYZ);
}

// Uniform noise of half-width `position` (unit) and `angle_deg` on camera_from_target.
Pose Noisy(const Pose& pose, double position, double angle_deg) {
  Pose noisy = pose;
  for (int k = 0; k < 3; ++k) noisy.position[k] += Uniform(-position, position);
  const Eigen::Vector3d axis_angle(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
  const Eigen::Vector3d rotation = axis_angle * DegToRad(angle_deg);
  if (rotation.norm() > 0)
    noisy.rotation = Eigen::AngleAxisd(rotation.norm(), rotation.normalized()).toRotationMatrix() * pose.rotation;
  return noisy;
}

struct Scene {
  std::vector<Pose> true_base_from_platform;
  CameraCalibrationInput input;
};

Scene MakeScene(const Robot& truth, const Robot& nominal, const std::vector<Vector6d>& poses, double position = 0,
                double angle_deg = 0, double leg = 0) {
  Scene scene;
  const Pose camera_from_base = Inverse(TrueBaseFromCamera());
  for (const Vector6d& v : poses) {
    const Pose base_from_platform = truth.PoseFromVector(v);
    scene.true_base_from_platform.push_back(base_from_platform);
    const Pose camera_from_target = Compose(Compose(camera_from_base, base_from_platform), TruePlatformFromTarget());
    scene.input.camera_from_target.push_back(Noisy(camera_from_target, position, angle_deg));
    LegReadings readings = InverseKinematics(truth, base_from_platform);
    for (int i = 0; i < kNumLegs; ++i) readings[i] += Uniform(-leg, leg);
    scene.input.legs.push_back(readings);
    scene.input.fk_start.push_back(nominal.PoseFromVector(v));
  }
  return scene;
}

::testing::AssertionResult PoseNear(const Pose& a, const Pose& b, double position, double angle_deg) {
  const double dp = (a.position - b.position).norm();
  const double da = RadToDeg(RotationDistance(a.rotation, b.rotation));
  if (dp <= position && da <= angle_deg) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "position differs by " << dp << ", rotation by " << da << " deg";
}

TEST(Rigid, ComposeAndInverse) {
  const Pose x = TrueBaseFromCamera();
  EXPECT_TRUE(PoseNear(Compose(x, Inverse(x)), Pose{}, 1e-12, 1e-10));
  const Eigen::Vector3d p(1, 2, 3);
  EXPECT_TRUE(MatrixNear(Compose(x, TruePlatformFromTarget()) * p, x * (TruePlatformFromTarget() * p), 1e-12));
}

TEST(Registration, ExactPosesGiveTheFramesBackLinearlyAndRefined) {
  const Robot robot = Preset("inria-left-hand");
  const Scene scene = MakeScene(robot, robot, RandomFeasiblePoses(robot, 12, 3));
  for (bool refine : {false, true}) {
    RegistrationOptions options;
    options.refine = refine;
    StatusOr<Registration> reg =
        EstimateRegistration(scene.true_base_from_platform, scene.input.camera_from_target, options);
    ASSERT_TRUE(reg.ok()) << reg.status().message();
    EXPECT_TRUE(PoseNear(reg->base_from_camera, TrueBaseFromCamera(), 1e-8, 1e-8));
    EXPECT_TRUE(PoseNear(reg->platform_from_target, TruePlatformFromTarget(), 1e-8, 1e-8));
    EXPECT_LT(reg->position_max, 1e-8);
    EXPECT_LT(reg->angle_max_deg, 1e-8);
  }
}

TEST(Registration, RefinementImprovesOnTheLinearEstimateWithNoise) {
  const Robot robot = Preset("inria-left-hand");
  const Scene scene = MakeScene(robot, robot, RandomFeasiblePoses(robot, 40, 5), 0.01, 0.05);
  RegistrationOptions linear_only;
  linear_only.refine = false;
  StatusOr<Registration> linear =
      EstimateRegistration(scene.true_base_from_platform, scene.input.camera_from_target, linear_only);
  RegistrationOptions refined_options;
  refined_options.position_sigma = 0.01;
  refined_options.angle_sigma_deg = 0.05;
  StatusOr<Registration> refined =
      EstimateRegistration(scene.true_base_from_platform, scene.input.camera_from_target, refined_options);
  ASSERT_TRUE(linear.ok() && refined.ok());
  EXPECT_GT(refined->iterations, 0);
  EXPECT_LE(refined->position_rms, linear->position_rms + 1e-12);
  EXPECT_TRUE(PoseNear(refined->base_from_camera, TrueBaseFromCamera(), 0.05, 0.05));
  EXPECT_TRUE(PoseNear(refined->platform_from_target, TruePlatformFromTarget(), 0.05, 0.05));
  EXPECT_LT(refined->position_rms, 0.03);
}

TEST(Registration, RejectsTooFewAndDegeneratePoses) {
  const Robot robot = Preset("inria-left-hand");
  const Scene scene = MakeScene(robot, robot, RandomFeasiblePoses(robot, 6, 7));
  std::vector<Pose> two(scene.true_base_from_platform.begin(), scene.true_base_from_platform.begin() + 2);
  std::vector<Pose> two_camera(scene.input.camera_from_target.begin(), scene.input.camera_from_target.begin() + 2);
  StatusOr<Registration> few = EstimateRegistration(two, two_camera);
  ASSERT_FALSE(few.ok());
  EXPECT_THAT(few.status().message(), HasSubstr("at least 3"));

  // Pure translations: the rotation about the motion is undetermined.
  std::vector<Pose> translated, camera;
  for (int j = 0; j < 6; ++j) {
    Pose a = robot.PoseFromVector((Vector6d() << j, 0.3 * j * j, 53, 0, 0, 0).finished());
    translated.push_back(a);
    camera.push_back(Compose(Compose(Inverse(TrueBaseFromCamera()), a), TruePlatformFromTarget()));
  }
  StatusOr<Registration> degenerate = EstimateRegistration(translated, camera);
  ASSERT_FALSE(degenerate.ok());
  EXPECT_THAT(degenerate.status().message(), HasSubstr("do not determine"));
}

// The gauge: the calibrated robot is the true robot expressed in the frames
// the nominal robot's registration defines, G = X X*⁻¹ and H = Y Y*⁻¹.
TEST(CalibrateFromCameraPoses, ExactDataGiveTheTrueParametersInTheRegisteredFrames) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const Scene scene = MakeScene(truth, nominal, RandomFeasiblePoses(nominal, 30, 11));
  StatusOr<CameraCalibrationResult> result = CalibrateFromCameraPoses(nominal, scene.input);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const Registration& reg = result->registration;
  const Pose gauge_base = Compose(reg.base_from_camera, Inverse(TrueBaseFromCamera()));
  const Pose gauge_platform = Compose(reg.platform_from_target, Inverse(TruePlatformFromTarget()));
  const Robot truth_in_gauge = ExpressInFrames(truth, gauge_base, gauge_platform);
  EXPECT_TRUE(MatrixNear(result->calibration.Estimates(), ParametersOf(truth_in_gauge), 1e-7));
  EXPECT_LT(result->calibrated_position_rms, 1e-8);
  EXPECT_LT(result->calibrated_angle_rms_deg, 1e-7);
  // The offsets l_i do not depend on the frames.
  for (int i = 0; i < kNumLegs; ++i) EXPECT_NEAR(result->calibration.robot.legs[i].offset, truth.legs[i].offset, 1e-7);
}

// The registered frames differ from the true ones by the gauge, which comes
// from the nominal robot's error: none for a perfect nominal robot, small for
// a nearly perfect one. (Legs of 52 cm between plates of 8–13 cm radius turn
// a 0.5 cm parameter error into degrees of pose error, and the camera 120 cm
// away turns that into centimetres.)
TEST(CalibrateFromCameraPoses, RegisteredFramesAreTheTrueOnesForAPerfectNominalRobot) {
  const Robot nominal = Preset("inria-left-hand");
  for (double half_width : {0.0, 0.002}) {
    const Robot truth = PerturbedRobot(nominal, half_width);
    const Scene scene = MakeScene(truth, nominal, RandomFeasiblePoses(nominal, 30, 11));
    StatusOr<CameraCalibrationResult> result = CalibrateFromCameraPoses(nominal, scene.input);
    ASSERT_TRUE(result.ok()) << result.status().message();
    const Registration& reg = result->registration;
    const double position = half_width == 0 ? 1e-8 : 0.2, angle = half_width == 0 ? 1e-7 : 0.3;
    EXPECT_TRUE(PoseNear(reg.base_from_camera, TrueBaseFromCamera(), position, angle)) << half_width;
    EXPECT_TRUE(PoseNear(reg.platform_from_target, TruePlatformFromTarget(), position, angle)) << half_width;
  }
}

// How many of the 42 estimates are within 3σ of the truth moved into the
// registered frames (the gauge, registration.h).
int CountWithinThreeSigma(const Robot& truth, const CameraCalibrationResult& result) {
  const Registration& reg = result.registration;
  const Robot truth_in_gauge = ExpressInFrames(truth, Compose(reg.base_from_camera, Inverse(TrueBaseFromCamera())),
                                               Compose(reg.platform_from_target, Inverse(TruePlatformFromTarget())));
  const ParameterVector error = result.calibration.Estimates() - ParametersOf(truth_in_gauge);
  const ParameterVector sigma = result.calibration.StdDevs();
  int inside = 0;
  for (int k = 0; k < kNumParams; ++k) inside += std::abs(error[k]) <= 3 * sigma[k];
  return inside;
}

TEST(CalibrateFromCameraPoses, NoisyDataStayWithinThreeSigmaOfTheTruthInTheRegisteredFrames) {
  const Robot nominal = Preset("inria-left-hand");
  int inside = 0, total = 0;
  for (int run = 0; run < 4; ++run) {
    const Robot truth = PerturbedRobot(nominal, 0.5);
    const Scene scene = MakeScene(truth, nominal, RandomFeasiblePoses(nominal, 40, 20 + run), 0.002, 0.02, 0.002);
    RegistrationOptions registration;
    registration.position_sigma = 0.002;
    registration.angle_sigma_deg = 0.02;
    StatusOr<CameraCalibrationResult> result = CalibrateFromCameraPoses(nominal, scene.input, registration);
    ASSERT_TRUE(result.ok()) << result.status().message();
    inside += CountWithinThreeSigma(truth, *result);
    total += kNumParams;
  }
  EXPECT_GE(inside, 0.95 * total) << inside << " of " << total << " within 3 sigma";
}

// The first-order map of a camera pose covariance to the base frame against a
// Monte Carlo estimate: sample the camera pose vector, map each sample.
TEST(MapCameraPoseCovariance, MatchesMonteCarlo) {
  const Robot nominal = Preset("inria-left-hand");
  Registration reg;
  reg.base_from_camera = TrueBaseFromCamera();
  reg.platform_from_target = TruePlatformFromTarget();
  const Pose camera_from_target = Compose(Compose(Inverse(TrueBaseFromCamera()),
                                                  nominal.PoseFromVector((Vector6d() << 3, -2, 52, 10, -5, 20).finished())),
                                          TruePlatformFromTarget());
  // Anisotropic and correlated, as a board pose's: depth worst, x with q2.
  Vector6d sigma;
  sigma << 0.002, 0.003, 0.01, 0.004, 0.003, 0.001;
  Matrix6d covariance = sigma.asDiagonal() * Matrix6d::Identity() * sigma.asDiagonal();
  covariance(0, 4) = covariance(4, 0) = 0.6 * sigma[0] * sigma[4];
  const Matrix6d mapped = MapCameraPoseCovariance(nominal, reg, camera_from_target, covariance);

  const Vector6d b = VectorFromPose(camera_from_target, EulerConvention::kXYZ);
  const Vector6d a = nominal.VectorFromPose(BaseFromPlatform(reg, camera_from_target));
  const Matrix6d root = covariance.llt().matrixL();
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  const int samples = 20000;
  Matrix6d sampled = Matrix6d::Zero();
  for (int n = 0; n < samples; ++n) {
    Vector6d z;
    for (int k = 0; k < 6; ++k) z[k] = normal(rng);
    const Vector6d d =
        nominal.VectorFromPose(BaseFromPlatform(reg, PoseFromVector(b + root * z, EulerConvention::kXYZ))) - a;
    sampled += d * d.transpose() / samples;
  }
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(mapped(k, k), sampled(k, k), 0.05 * sampled(k, k)) << "variance " << k;
  }
  // The map is not the identity: the camera looks down from 120 units, turned.
  EXPECT_GT((mapped - covariance).norm(), 0.1 * covariance.norm());
}

// Per-image covariances (depth noise 5 times the lateral, changing from image
// to image, as a camera gives) weight the calibration; with σ at least a
// priori, the truth in the registered frames is within 3σ for ≥ 95 % of the
// parameters and the variance factors are near 1.
TEST(CalibrateFromCameraPoses, PerImageCovariancesGiveTrustworthySigmas) {
  const Robot nominal = Preset("inria-left-hand");
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  int inside = 0, total = 0;
  double variance_factor_sum = 0;
  for (int run = 0; run < 4; ++run) {
    const Robot truth = PerturbedRobot(nominal, 0.5);
    Scene scene = MakeScene(truth, nominal, RandomFeasiblePoses(nominal, 30, 40 + run), 0, 0, 0.001);
    for (Pose& camera_from_target : scene.input.camera_from_target) {
      const double scale = Uniform(0.5, 3);
      Vector6d sigma;
      sigma << 0.0005 * scale, 0.0005 * scale, 0.0025 * scale, 0.003 * scale, 0.003 * scale, 0.0006 * scale;
      Vector6d v = VectorFromPose(camera_from_target, EulerConvention::kXYZ);
      for (int k = 0; k < 6; ++k) v[k] += sigma[k] * normal(rng);
      camera_from_target = PoseFromVector(v, EulerConvention::kXYZ);
      scene.input.camera_pose_covariance.push_back(sigma.array().square().matrix().asDiagonal());
    }
    CalibrationOptions calibration;
    calibration.weighted = true;
    calibration.noise.leg = 0.001;
    calibration.uncertainty_scale = UncertaintyScale::kAtLeastAPriori;
    RegistrationOptions registration;
    registration.position_sigma = 0.001;
    registration.angle_sigma_deg = 0.003;
    StatusOr<CameraCalibrationResult> result = CalibrateFromCameraPoses(nominal, scene.input, registration, calibration);
    ASSERT_TRUE(result.ok()) << result.status().message();
    inside += CountWithinThreeSigma(truth, *result);
    total += kNumParams;
    for (const LegCalibration& leg : result->calibration.legs) variance_factor_sum += leg.variance_factor;
  }
  EXPECT_GE(inside, 0.95 * total) << inside << " of " << total << " within 3 sigma";
  const double mean_variance_factor = variance_factor_sum / (4 * kNumLegs);
  EXPECT_GT(mean_variance_factor, 0.6);
  EXPECT_LT(mean_variance_factor, 1.6);
}

// A reading 1 cm off (outlier_screening.h) is named and left out of its leg's
// fit; its image's FK pose is wrong too, so it is left out of the registration:
// frames, closure and parameters as with clean data.
TEST(CalibrateFromCameraPoses, AWrongReadingIsLeftOutOfTheFitAndOfTheRegistration) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const Scene clean = MakeScene(truth, nominal, RandomFeasiblePoses(nominal, 24, 31), 0.002, 0.02, 0.002);
  Scene bad = clean;
  bad.input.legs[5][1] += 1.0;
  RegistrationOptions registration;
  registration.position_sigma = 0.002;
  registration.angle_sigma_deg = 0.02;
  CalibrationOptions calibration;
  calibration.weighted = true;
  calibration.noise = {0.002, 0.02, 0.002};
  calibration.outliers.enabled = true;
  StatusOr<CameraCalibrationResult> reference =
      CalibrateFromCameraPoses(nominal, clean.input, registration, calibration);
  StatusOr<CameraCalibrationResult> screened = CalibrateFromCameraPoses(nominal, bad.input, registration, calibration);
  ASSERT_TRUE(reference.ok()) << reference.status().message();
  ASSERT_TRUE(screened.ok()) << screened.status().message();
  EXPECT_TRUE(reference->registration_left_out.empty());
  EXPECT_EQ(screened->registration_left_out, std::vector<int>{5});
  for (int i = 0; i < kNumLegs; ++i) {
    EXPECT_TRUE(reference->calibration.legs[i].outliers.empty()) << "leg " << i + 1;
    EXPECT_EQ(screened->calibration.legs[i].outliers.size(), i == 1 ? 1u : 0u) << "leg " << i + 1;
  }
  EXPECT_EQ(screened->calibration.legs[1].outliers[0].measurement, 5);
  EXPECT_TRUE(PoseNear(screened->registration.base_from_camera, reference->registration.base_from_camera, 0.05, 0.05));
  EXPECT_LT(screened->registration.position_rms, 1.2 * reference->registration.position_rms);
  EXPECT_LT(screened->calibrated_position_rms, 1.2 * reference->calibrated_position_rms);
  EXPECT_GE(CountWithinThreeSigma(truth, *screened), 40);
}

TEST(CalibrateFromCameraPoses, RejectsCovariancesOfAnotherCountOrNotFinite) {
  const Robot nominal = Preset("inria-left-hand");
  Scene scene = MakeScene(nominal, nominal, RandomFeasiblePoses(nominal, 12, 5));
  scene.input.camera_pose_covariance.assign(11, Matrix6d::Identity() * 1e-6);
  StatusOr<CameraCalibrationResult> result = CalibrateFromCameraPoses(nominal, scene.input);
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.status().message(), HasSubstr("differ in number"));
  scene.input.camera_pose_covariance.assign(12, Matrix6d::Identity() * 1e-6);
  scene.input.camera_pose_covariance[4](2, 2) = std::nan("");
  result = CalibrateFromCameraPoses(nominal, scene.input);
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.status().message(), HasSubstr("pose 5: the camera pose covariance is not finite"));
}

}  // namespace
}  // namespace hexcal

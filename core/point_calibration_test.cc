#include "core/point_calibration.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <random>

#include "core/inverse_kinematics.h"
#include "core/point_calibration_cost.h"
#include "core/registration.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using testing::Accuracy;
using testing::AccuracyInRegisteredFrames;
using testing::MatrixNear;
using testing::PerturbedRobot;
using testing::Preset;
using testing::SpreadFeasiblePoses;

// A simulated tracker session, independent of the fit: the true robot at
// random poses, a tracker 1.2 platform radii above the base at an unknown
// frame X*, 4 reflectors over the platform given in a frame Y* fixed to it,
// each measured with N(0, σ²) per coordinate; the legs read with uniform noise
// ±leg_noise. Lengths in the robot's unit.
struct TrackerScene {
  Robot nominal, truth;
  Pose base_from_tracker, platform_from_reflectors;  // X*, Y*
  std::vector<NamedPoint> reflectors;                // in the reflector frame
  std::vector<Pose> poses;
  std::vector<LegReadings> legs;
  std::vector<std::vector<NamedPoint>> seen;  // tracker frame
  double sigma = 0, leg_noise = 0;
};

TrackerScene MakeTrackerScene(const std::string& robot, int poses, double sigma, double leg_noise, double perturb,
                              uint64_t seed) {
  TrackerScene scene;
  scene.nominal = Preset(robot);
  scene.truth = PerturbedRobot(scene.nominal, perturb);
  scene.sigma = sigma;
  scene.leg_noise = leg_noise;
  double radius = 0;
  for (const Leg& leg : scene.nominal.legs) radius = std::max(radius, leg.b_in_platform.head<2>().norm());
  Vector6d tracker;
  tracker << 0.1 * radius, -0.2 * radius, 12 * radius, 178, 3, -20;
  scene.base_from_tracker = PoseFromVector(tracker, EulerConvention::kXYZ);
  Vector6d reflector_frame;
  reflector_frame << 0.02 * radius, -0.01 * radius, 0.05 * radius, 2, -1, 30;
  scene.platform_from_reflectors = PoseFromVector(reflector_frame, EulerConvention::kXYZ);
  const std::vector<Eigen::Vector3d> on_platform = {{radius, 0, 0.1 * radius},
                                                    {-0.5 * radius, 0.85 * radius, 0},
                                                    {-0.5 * radius, -0.85 * radius, 0.2 * radius},
                                                    {0, 0.1 * radius, 0.4 * radius}};
  const Pose reflectors_from_platform = Inverse(scene.platform_from_reflectors);
  for (size_t k = 0; k < on_platform.size(); ++k)
    scene.reflectors.push_back({"R" + std::to_string(k + 1), reflectors_from_platform * on_platform[k], 0});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> legs_noise(-leg_noise, leg_noise);
  std::normal_distribution<double> point_noise(0, sigma);
  for (const Vector6d& v : SpreadFeasiblePoses(scene.truth, poses, seed)) {
    const Pose pose = scene.truth.PoseFromVector(v);
    LegReadings legs = InverseKinematics(scene.truth, pose);
    for (int i = 0; i < kNumLegs; ++i) legs[i] += legs_noise(rng);
    const Pose tracker_from_reflectors =
        Compose(Inverse(scene.base_from_tracker), Compose(pose, scene.platform_from_reflectors));
    std::vector<NamedPoint> points;
    for (const NamedPoint& r : scene.reflectors) {
      const Eigen::Vector3d noise(point_noise(rng), point_noise(rng), point_noise(rng));
      points.push_back({r.name, tracker_from_reflectors * r.position + noise, sigma});
    }
    scene.poses.push_back(pose);
    scene.legs.push_back(legs);
    scene.seen.push_back(points);
  }
  return scene;
}

// The two-stage calibration as a points session runs it: each pose fitted to
// its points (core/point_fit.h), the frames registered with the nominal
// robot, the legs fitted to the poses weighted by their covariance.
CameraCalibrationResult TwoStage(const TrackerScene& scene) {
  CameraCalibrationInput input;
  std::vector<double> position_sigma, angle_sigma;
  for (size_t j = 0; j < scene.poses.size(); ++j) {
    StatusOr<PointFit> fit = FitPointPose(scene.reflectors, scene.seen[j]);
    EXPECT_TRUE(fit.ok()) << fit.status().message();
    input.camera_from_target.push_back(fit->pose);
    input.camera_pose_covariance.push_back(fit->covariance);
    input.legs.push_back(scene.legs[j]);
    input.fk_start.push_back(scene.poses[j]);
    position_sigma.push_back(std::sqrt(fit->covariance.topLeftCorner<3, 3>().trace() / 3));
    angle_sigma.push_back(std::sqrt(fit->covariance.bottomRightCorner<3, 3>().trace() / 3));
  }
  std::sort(position_sigma.begin(), position_sigma.end());
  std::sort(angle_sigma.begin(), angle_sigma.end());
  NoiseModel noise;  // as point_session.cc: √3 × the median pose σ
  noise.position = std::sqrt(3.0) * position_sigma[position_sigma.size() / 2];
  noise.angle_deg = std::sqrt(3.0) * angle_sigma[angle_sigma.size() / 2];
  noise.leg = scene.leg_noise;
  CalibrationOptions calibration;
  calibration.weighted = true;
  calibration.noise = noise;
  calibration.uncertainty_scale = UncertaintyScale::kAtLeastAPriori;
  StatusOr<CameraCalibrationResult> result =
      CalibrateFromCameraPoses(scene.nominal, input, RegistrationOptionsFromNoise(noise), calibration);
  EXPECT_TRUE(result.ok()) << result.status().message();
  return result.ok() ? *result : CameraCalibrationResult{};
}

// The joint fit's input as a session gives it: started from the two-stage
// calibration, in its registered frames, the reflectors Y·p_k.
PointCalibrationInput InputOf(const TrackerScene& scene, const CameraCalibrationResult& two_stage) {
  PointCalibrationInput input{
      scene.nominal, two_stage.calibration.robot, two_stage.registration.base_from_camera, {}, {}};
  for (const NamedPoint& r : scene.reflectors)
    input.reflectors.push_back({r.name, two_stage.registration.platform_from_target * r.position, 0});
  for (size_t j = 0; j < scene.poses.size(); ++j) {
    PointCalibrationPose pose;
    pose.name = "pose_" + std::to_string(j);
    pose.points = scene.seen[j];
    pose.legs = scene.legs[j];
    pose.base_from_platform = scene.nominal.PoseFromVector(two_stage.measurements[j].pose);
    input.poses.push_back(pose);
  }
  return input;
}

PointCalibrationOptions Options(const TrackerScene& scene) {
  PointCalibrationOptions options;
  options.leg_sigma = scene.leg_noise / std::sqrt(3.0);
  return options;
}

// Errors against the truth in the registered frames (the gauge: X fixed, the
// reflectors' placement Y·p_k, which the truth's reflectors have exactly).
Accuracy AccuracyOf(const CalibrationResult& fit, const TrackerScene& scene, const Registration& frames) {
  return AccuracyInRegisteredFrames(fit, scene.truth, scene.base_from_tracker, scene.platform_from_reflectors, frames);
}

struct RobotCase {
  const char* robot;
  double sigma, leg_noise, perturb;  // robot unit
};

class JointFitOnBothRobots : public ::testing::TestWithParam<RobotCase> {};

// σ 0.02 mm per coordinate, readings ±0.01 mm, every parameter ±0.5 mm, as
// `hexcal demo --instrument points`.
INSTANTIATE_TEST_SUITE_P(Robots, JointFitOnBothRobots,
                         ::testing::Values(RobotCase{"inria-left-hand", 0.002, 0.001, 0.05},
                                           RobotCase{"deltalab-table", 0.02, 0.01, 0.5}));

TEST_P(JointFitOnBothRobots, RecoversTheTruthAtLeastAsWellAsTwoStage) {
  const RobotCase c = GetParam();
  double joint_sum = 0, two_stage_sum = 0;
  int seeds = 0;
  for (uint64_t seed : {3, 4, 5}) {
    const TrackerScene scene = MakeTrackerScene(c.robot, 40, c.sigma, c.leg_noise, c.perturb, seed);
    const CameraCalibrationResult two_stage = TwoStage(scene);
    const PointCalibrationInput input = InputOf(scene, two_stage);
    StatusOr<PointCalibrationResult> fit = CalibrateFromPoints(input, Options(scene));
    ASSERT_TRUE(fit.ok()) << fit.status().message();
    const Accuracy joint = AccuracyOf(fit->calibration, scene, two_stage.registration);
    const Accuracy poses = AccuracyOf(two_stage.calibration, scene, two_stage.registration);
    std::printf("%s seed %d: joint %.5g (%.3f within 3 sigma), two-stage %.5g (%.3f); s2 %.3f, rank %d of %d\n",
                c.robot, static_cast<int>(seed), joint.mean_error, joint.within_3sigma, poses.mean_error,
                poses.within_3sigma, fit->variance_factor, fit->identifiability.rank, fit->identifiability.unknowns);
    EXPECT_GE(joint.within_3sigma, 0.95);
    EXPECT_NEAR(fit->variance_factor, 1.0, 0.25);
    EXPECT_EQ(fit->identifiability.unknowns, 42 + 12 - 6);
    EXPECT_EQ(fit->identifiability.rank, fit->identifiability.unknowns);
    EXPECT_EQ(fit->points, 4 * 40);
    EXPECT_NEAR(fit->point_rms, c.sigma * std::sqrt(3.0), 0.2 * c.sigma * std::sqrt(3.0));
    // The reflectors: the true ones are Y·p_k in the gauge (the file is exact).
    for (size_t k = 0; k < input.reflectors.size(); ++k) {
      const Eigen::Vector3d error = fit->reflectors[k].position - input.reflectors[k].position;
      const Eigen::Matrix3d covariance = fit->reflector_covariance.block<3, 3>(3 * k, 3 * k);
      EXPECT_LT(error.dot((covariance + 1e-30 * Eigen::Matrix3d::Identity()).ldlt().solve(error)), 30)
          << fit->reflectors[k].name;  // χ²₃ tail (rank-deficient covariance: the gauge)
    }
    joint_sum += joint.mean_error;
    two_stage_sum += poses.mean_error;
    ++seeds;
  }
  std::printf("%s: mean parameter error joint %.5g, two-stage %.5g over %d seeds\n", c.robot, joint_sum / seeds,
              two_stage_sum / seeds, seeds);
  EXPECT_LE(joint_sum, two_stage_sum * 1.05);
}

TEST(CalibrateFromPoints, HoldsTheGaugeOfTheReflectors) {
  const TrackerScene scene = MakeTrackerScene("inria-left-hand", 20, 0.002, 0.001, 0.05, 9);
  const CameraCalibrationResult two_stage = TwoStage(scene);
  const PointCalibrationInput input = InputOf(scene, two_stage);
  StatusOr<PointCalibrationResult> fit = CalibrateFromPoints(input, Options(scene));
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  Eigen::VectorXd start(12), moved(12);
  for (int k = 0; k < 4; ++k) {
    start.segment<3>(3 * k) = input.reflectors[k].position;
    moved.segment<3>(3 * k) = fit->reflectors[k].position - input.reflectors[k].position;
  }
  EXPECT_LT((ReflectorGaugeConstraints(start) * moved).norm(), 1e-12);
  EXPECT_GT(moved.norm(), 0);  // they were estimated
  // The covariance has the gauge's 6 null directions and no others.
  EXPECT_LT((ReflectorGaugeConstraints(start) * fit->reflector_covariance).norm(),
            1e-9 * fit->reflector_covariance.norm());
  // Held: nothing moves, no σ, 42 unknowns.
  PointCalibrationOptions held = Options(scene);
  held.estimate_reflectors = false;
  StatusOr<PointCalibrationResult> fixed = CalibrateFromPoints(input, held);
  ASSERT_TRUE(fixed.ok()) << fixed.status().message();
  EXPECT_EQ(fixed->identifiability.unknowns, 42);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(fixed->reflectors[k].position, input.reflectors[k].position);
  EXPECT_TRUE(fixed->reflector_covariance.isZero(0));
}

// The point residual's Jacobian (Ceres' dual numbers scattered into the
// reflectors' block) against central differences of the residual computed
// with Eigen's own rotation, on both blocks.
TEST(PointResidualCost, JacobianMatchesFiniteDifferences) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  Vector6d tracker;
  tracker << 3, -2, 120, 175, 4, -30;
  const Pose base_from_tracker = PoseFromVector(tracker, EulerConvention::kXYZ);
  const Eigen::Vector3d measured(1.5, -2.5, 110);
  const double sigma = 0.003;
  const int count = 4, which = 2;
  double pose[6] = {0.3, -0.2, 0.5, 1.0, -2.0, 25.0};
  Eigen::VectorXd reflectors(3 * count);
  for (int k = 0; k < 3 * count; ++k) reflectors[k] = 8 * u(rng);
  auto residual = [&](const double* p, const Eigen::VectorXd& r) {
    const Eigen::Vector3d omega(p[0], p[1], p[2]);
    const Eigen::Matrix3d rotation = omega.norm() > 0
                                         ? Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix()
                                         : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d in_base = rotation * r.segment<3>(3 * which) + Eigen::Vector3d(p[3], p[4], p[5]);
    return Eigen::Vector3d((Inverse(base_from_tracker) * in_base - measured) / sigma);
  };
  const PointResidualCost cost(base_from_tracker, measured, sigma, which, count);
  Eigen::Matrix<double, 3, 6, Eigen::RowMajor> d_pose;
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> d_reflectors(3, 3 * count);
  Eigen::Vector3d r;
  const double* parameters[2] = {pose, reflectors.data()};
  double* jacobians[2] = {d_pose.data(), d_reflectors.data()};
  ASSERT_TRUE(cost.Evaluate(parameters, r.data(), jacobians));
  EXPECT_TRUE(MatrixNear(r, residual(pose, reflectors), 1e-9));
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    double plus[6], minus[6];
    std::copy(pose, pose + 6, plus);
    std::copy(pose, pose + 6, minus);
    plus[k] += h;
    minus[k] -= h;
    const Eigen::Vector3d numeric = (residual(plus, reflectors) - residual(minus, reflectors)) / (2 * h);
    EXPECT_TRUE(MatrixNear(Eigen::Vector3d(d_pose.col(k)), numeric, 1e-5 * (1 + numeric.norm()))) << "pose " << k;
  }
  for (int k = 0; k < 3 * count; ++k) {
    Eigen::VectorXd plus = reflectors, minus = reflectors;
    plus[k] += h;
    minus[k] -= h;
    const Eigen::Vector3d numeric = (residual(pose, plus) - residual(pose, minus)) / (2 * h);
    EXPECT_TRUE(MatrixNear(Eigen::Vector3d(d_reflectors.col(k)), numeric, 1e-5 * (1 + numeric.norm())))
        << "reflector coordinate " << k;
  }
}

TEST(ReflectorGaugeManifold, MovesOnlyWithinTheGaugeAndRefusesALine) {
  Eigen::VectorXd start(12);
  start << 7, 0, 0.7, -3.5, 6, 0, -3.5, -6, 1.4, 0, 0.7, 2.8;
  const ReflectorGaugeManifold gauge(start);
  ASSERT_TRUE(gauge.valid());
  EXPECT_EQ(gauge.TangentSize(), 6);
  EXPECT_TRUE(
      MatrixNear(Eigen::MatrixXd(gauge.basis().transpose() * gauge.basis()), Eigen::MatrixXd::Identity(6, 6), 1e-12));
  Eigen::VectorXd delta(6), moved(12), back(6);
  delta << 0.1, -0.2, 0.3, 0.05, 0, -0.4;
  gauge.Plus(start.data(), delta.data(), moved.data());
  EXPECT_LT((ReflectorGaugeConstraints(start) * (moved - start)).norm(), 1e-12);
  gauge.Minus(moved.data(), start.data(), back.data());
  EXPECT_TRUE(MatrixNear(back, delta, 1e-12));
  Eigen::VectorXd line(9);
  line << 0, 0, 0, 1, 1, 1, 2, 2, 2;
  EXPECT_FALSE(ReflectorGaugeManifold(line).valid());
}

// Not identifiable: each refused with its reason named.
TEST(CalibrateFromPoints, RefusesWhatTheDataCannotDetermine) {
  const TrackerScene scene = MakeTrackerScene("inria-left-hand", 12, 0.002, 0.001, 0.05, 2);
  const CameraCalibrationResult two_stage = TwoStage(scene);
  const PointCalibrationInput input = InputOf(scene, two_stage);

  PointCalibrationInput few = input;
  few.poses.resize(6);
  StatusOr<PointCalibrationResult> fit = CalibrateFromPoints(few, Options(scene));
  ASSERT_FALSE(fit.ok());
  EXPECT_EQ(fit.status().kind(), StatusKind::kBadInput);
  EXPECT_NE(fit.status().message().find("6 poses; at least 7 are needed"), std::string::npos) << fit.status().message();

  // The reflectors on one line: the rotation about it is free.
  PointCalibrationInput line = input;
  line.reflectors.resize(3);
  const Eigen::Vector3d a = line.reflectors[0].position, b = line.reflectors[1].position;
  line.reflectors[2].position = a + 0.5 * (b - a);
  for (PointCalibrationPose& pose : line.poses) pose.points.resize(3);
  fit = CalibrateFromPoints(line, Options(scene));
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("the reflectors R1, R2, R3 lie on one line"), std::string::npos)
      << fit.status().message();

  // Every pose the same: the legs' parameters cannot be separated.
  PointCalibrationInput still = input;
  for (PointCalibrationPose& pose : still.poses) pose = input.poses[0];
  fit = CalibrateFromPoints(still, Options(scene));
  ASSERT_FALSE(fit.ok());
  EXPECT_EQ(fit.status().kind(), StatusKind::kFailed);
  EXPECT_NE(fit.status().message().find("the data do not determine every unknown"), std::string::npos)
      << fit.status().message();
  EXPECT_NE(fit.status().message().find("weakest direction moves leg"), std::string::npos) << fit.status().message();
  std::printf("every pose the same: %s\n", fit.status().message().c_str());

  // A pose with 2 points, a point of no reflector, a bad σ: named.
  PointCalibrationInput two = input;
  two.poses[3].points.resize(2);
  fit = CalibrateFromPoints(two, Options(scene));
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("pose 'pose_3': 2 points"), std::string::npos) << fit.status().message();
  PointCalibrationInput unknown = input;
  unknown.poses[4].points[1].name = "R9";
  fit = CalibrateFromPoints(unknown, Options(scene));
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("point 'R9' is not among the reflectors"), std::string::npos);
  PointCalibrationOptions no_noise = Options(scene);
  no_noise.leg_sigma = 0;
  fit = CalibrateFromPoints(input, no_noise);
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("leg_sigma"), std::string::npos);
}

TEST(CalibrateFromPoints, StopsWhenCancelled) {
  const TrackerScene scene = MakeTrackerScene("inria-left-hand", 10, 0.002, 0.001, 0.05, 2);
  std::atomic<bool> cancel{true};
  StatusOr<PointCalibrationResult> fit =
      CalibrateFromPoints(InputOf(scene, TwoStage(scene)), Options(scene), JobHooks{nullptr, &cancel});
  EXPECT_TRUE(fit.status().cancelled());
}

}  // namespace
}  // namespace hexcal

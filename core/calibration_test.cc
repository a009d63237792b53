// The implicit calibration against independent truth: a robot perturbed here,
// measurements made here with its inverse kinematics. Exact data must give the
// truth back to 1e-9; noisy data must stay within the reported 3σ; bad pose
// sets must fail with a reason, never with numbers.
#include "core/calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "core/calibration_cost.h"
#include "core/candidates.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::Preset;
using ::hexcal::testing::TestRng;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

using ::hexcal::testing::PerturbedRobot;
using ::hexcal::testing::RandomFeasiblePoses;

// Uniform noise of half-widths (position, angle in degrees, leg); zero gives exact data.
std::vector<Measurement> Measure(const Robot& truth, const std::vector<Vector6d>& poses, double position = 0,
                                 double angle_deg = 0, double leg = 0) {
  std::vector<Measurement> measurements;
  for (const Vector6d& v : poses) {
    Measurement m;
    m.legs = InverseKinematics(truth, truth.PoseFromVector(v));
    m.pose = v;
    for (int k = 0; k < 6; ++k) m.pose[k] += Uniform(-1, 1) * (k < 3 ? position : angle_deg);
    for (int i = 0; i < kNumLegs; ++i) m.legs[i] += Uniform(-1, 1) * leg;
    measurements.push_back(m);
  }
  return measurements;
}

CalibrationResult CalibrateOk(const Robot& nominal, const std::vector<Measurement>& measurements,
                              const CalibrationOptions& options = {}) {
  StatusOr<CalibrationResult> result = Calibrate(nominal, measurements, options);
  EXPECT_TRUE(result.ok()) << result.status().message();
  return result.ok() ? *result : CalibrationResult{};
}

std::string CalibrateError(const Robot& nominal, const std::vector<Measurement>& measurements,
                           const CalibrationOptions& options = {}) {
  return testing::ErrorMessage(Calibrate(nominal, measurements, options), "this calibration");
}

TEST(ImplicitLegCost, JacobianMatchesCentralDifferences) {
  const Robot robot = Preset("inria-left-hand");
  for (double weight : {1.0, 0.037}) {
    for (int trial = 0; trial < 5; ++trial) {
      Vector6d v;
      v << Uniform(-3, 3), Uniform(-3, 3), Uniform(52, 55), Uniform(-15, 15), Uniform(-15, 15), Uniform(-15, 15);
      const ImplicitLegCost cost(robot.PoseFromVector(v), Uniform(0, 3.5), weight);
      LegParameters p = LegParametersOf(robot.legs[trial]);
      p += LegParameters::Random() * 0.5;
      const double* parameters[] = {p.data()};
      double residual = 0;
      JacobianRow analytic;
      double* jacobians[] = {analytic.data()};
      ASSERT_TRUE(cost.Evaluate(parameters, &residual, jacobians));
      JacobianRow numeric;
      for (int k = 0; k < kParamsPerLeg; ++k) {
        const double h = 1e-5;
        LegParameters plus = p, minus = p;
        plus[k] += h;
        minus[k] -= h;
        double r_plus = 0, r_minus = 0;
        const double* p_plus[] = {plus.data()};
        const double* p_minus[] = {minus.data()};
        cost.Evaluate(p_plus, &r_plus, nullptr);
        cost.Evaluate(p_minus, &r_minus, nullptr);
        numeric[k] = (r_plus - r_minus) / (2 * h);
      }
      EXPECT_TRUE(MatrixNear(analytic, numeric, 1e-6 * (1 + analytic.cwiseAbs().maxCoeff()))) << "weight " << weight;
    }
  }
}

TEST(Calibration, ExactDataFromAPerturbedRobotGiveTheTruthBack) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const std::vector<Measurement> measurements = Measure(truth, RandomFeasiblePoses(nominal, 25, 11));
  for (RobustLoss loss : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    for (bool weighted : {false, true}) {
      CalibrationOptions options;
      options.loss = loss;
      options.loss_scale = weighted ? 2.0 : 0.01;
      options.weighted = weighted;
      const CalibrationResult result = CalibrateOk(nominal, measurements, options);
      EXPECT_TRUE(MatrixNear(result.Estimates(), ParametersOf(truth), 1e-9))
          << RobustLossName(loss) << (weighted ? " weighted" : "");
      EXPECT_TRUE(MatrixNear(ParametersOf(result.robot), ParametersOf(truth), 1e-9));
      for (const LegCalibration& leg : result.legs) {
        EXPECT_EQ(leg.termination, "CONVERGENCE");
        EXPECT_LT(leg.residual_rms, 1e-10);
        EXPECT_GT(leg.iterations, 0);
      }
    }
  }
}

TEST(Calibration, WorksForAMillimetreRobotWithZyxAngles) {
  Robot nominal = Preset("deltalab-table");
  nominal.euler = EulerConvention::kZYX;
  const Robot truth = PerturbedRobot(nominal, 2.0);
  const CalibrationResult result = CalibrateOk(nominal, Measure(truth, RandomFeasiblePoses(nominal, 20, 5)));
  EXPECT_TRUE(MatrixNear(result.Estimates(), ParametersOf(truth), 1e-8));
}

TEST(Calibration, NoisyEstimatesFallWithinThreeReportedSigmas) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const std::vector<Vector6d> poses = RandomFeasiblePoses(nominal, 30, 3);
  int inside = 0, total = 0;
  for (int run = 0; run < 20; ++run) {
    const CalibrationResult result = CalibrateOk(nominal, Measure(truth, poses, 0.001, 0.01, 0.001));
    const ParameterVector error = (result.Estimates() - ParametersOf(truth)).cwiseAbs();
    const ParameterVector sigma = result.StdDevs();
    for (int k = 0; k < kNumParams; ++k) {
      ASSERT_GT(sigma[k], 0);
      inside += error[k] <= 3 * sigma[k];
      ++total;
    }
  }
  EXPECT_GE(inside, 0.95 * total) << inside << " of " << total << " within 3 sigma";
}

// σ from ceres::Covariance against s² (JᵀJ)⁻¹ assembled here from eq. 5.
TEST(Calibration, CovarianceIsTheScaledInverseInformation) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const std::vector<Measurement> measurements = Measure(truth, RandomFeasiblePoses(nominal, 15, 8), 0.002, 0.02, 0.002);
  const CalibrationResult result = CalibrateOk(nominal, measurements);
  for (int i = 0; i < kNumLegs; ++i) {
    const LegCalibration& leg = result.legs[i];
    ASSERT_TRUE(leg.has_uncertainty);
    const Robot& calibrated = result.robot;
    Eigen::MatrixXd jacobian(measurements.size(), kParamsPerLeg);
    double sum_squares = 0;
    for (size_t j = 0; j < measurements.size(); ++j) {
      const Pose pose = calibrated.PoseFromVector(measurements[j].pose);
      jacobian.row(j) = ImplicitJacobianRow(calibrated.legs[i], pose, measurements[j].legs[i]);
      sum_squares += std::pow(ImplicitResidual(calibrated.legs[i], pose, measurements[j].legs[i]), 2);
    }
    const double s2 = sum_squares / (measurements.size() - kParamsPerLeg);
    EXPECT_NEAR(leg.variance_factor, s2, 1e-6 * s2);
    const InfoBlock expected = s2 * (jacobian.transpose() * jacobian).inverse();
    EXPECT_TRUE(MatrixNear(leg.covariance, expected, 1e-6 * expected.cwiseAbs().maxCoeff())) << "leg " << i + 1;
    EXPECT_TRUE(MatrixNear(leg.singular_values, Eigen::JacobiSVD<Eigen::MatrixXd>(jacobian).singularValues(),
                           1e-6 * leg.singular_values[0]));
  }
}

TEST(Calibration, WeightingByTheTrueNoiseModelGivesAVarianceFactorNearOne) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  CalibrationOptions options;
  options.weighted = true;
  options.noise = {0.002, 0.02, 0.002};
  const std::vector<Measurement> measurements = Measure(
      truth, RandomFeasiblePoses(nominal, 60, 4), options.noise.position, options.noise.angle_deg, options.noise.leg);
  const CalibrationResult result = CalibrateOk(nominal, measurements, options);
  double mean_factor = 0;
  for (const LegCalibration& leg : result.legs) mean_factor += leg.variance_factor / kNumLegs;
  EXPECT_GT(mean_factor, 0.7);
  EXPECT_LT(mean_factor, 1.4);
}

TEST(Calibration, RobustLossResistsAnOutlier) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  std::vector<Measurement> measurements = Measure(truth, RandomFeasiblePoses(nominal, 30, 9), 0.0005, 0.005, 0.0005);
  measurements[4].legs[2] += 0.5;  // a misread sensor on leg 3
  const double plain_error =
      (CalibrateOk(nominal, measurements).legs[2].estimate - LegParametersOf(truth.legs[2])).cwiseAbs().maxCoeff();
  CalibrationOptions options;
  options.loss = RobustLoss::kCauchy;
  options.loss_scale = 0.005;  // cm of leg length
  const double robust_error =
      (CalibrateOk(nominal, measurements, options).legs[2].estimate - LegParametersOf(truth.legs[2]))
          .cwiseAbs()
          .maxCoeff();
  EXPECT_LT(robust_error, 0.1 * plain_error) << "plain " << plain_error << ", robust " << robust_error;
}

// Rotations about z only, up to a tiny tilt: moving a_z and b_z together barely changes any leg length.
TEST(Calibration, ReportsTheDirectionThePosesCannotSee) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  std::vector<Vector6d> poses;
  for (int j = 0; j < 20; ++j) {
    Vector6d v;
    v << Uniform(-2, 2), Uniform(-2, 2), Uniform(52.5, 54.5), Uniform(-0.01, 0.01), Uniform(-0.01, 0.01),
        Uniform(-10, 10);
    poses.push_back(v);
  }
  CalibrationOptions options;
  options.weak_direction_ratio = 1e-3;
  const CalibrationResult result = CalibrateOk(nominal, Measure(truth, poses, 1e-5, 1e-5, 1e-5), options);
  LegParameters expected = LegParameters::Zero();
  expected[2] = expected[5] = std::sqrt(0.5);  // δa_z = δb_z
  for (const LegCalibration& leg : result.legs) {
    ASSERT_FALSE(leg.unidentifiable.empty());
    const WeakDirection& weakest = leg.unidentifiable.back();
    EXPECT_NEAR(weakest.ratio, leg.singular_values[6] / leg.singular_values[0], 1e-15);
    EXPECT_GT(std::abs(weakest.direction.dot(expected)), 0.99) << weakest.direction.transpose();
    const bool az_bz_correlated =
        std::any_of(leg.correlated.begin(), leg.correlated.end(),
                    [](const CorrelatedPair& c) { return c.first == 2 && c.second == 5 && c.correlation > 0.95; });
    EXPECT_TRUE(az_bz_correlated);
  }
}

TEST(Calibration, SevenMeasurementsFitExactlyWithoutUncertainty) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const CalibrationResult result = CalibrateOk(nominal, Measure(truth, RandomFeasiblePoses(nominal, 7, 2)));
  EXPECT_TRUE(MatrixNear(result.Estimates(), ParametersOf(truth), 1e-8));
  for (const LegCalibration& leg : result.legs) EXPECT_FALSE(leg.has_uncertainty);
}

TEST(Calibration, FewerThanSevenMeasurementsIsAnError) {
  const Robot nominal = Preset("inria-left-hand");
  EXPECT_THAT(CalibrateError(nominal, Measure(nominal, RandomFeasiblePoses(nominal, 6, 1))),
              HasSubstr("at least 7 measurements (7 parameters per leg), got 6"));
}

// mm readings for a cm robot: ten times too long, far outside the stroke.
TEST(Calibration, ReadingsInAnotherUnitAreAnError) {
  const Robot nominal = Preset("inria-left-hand");
  std::vector<Measurement> measurements = Measure(nominal, RandomFeasiblePoses(nominal, 12, 4));
  ASSERT_TRUE(CheckCalibrationInput(nominal, measurements, {}).ok());
  for (Measurement& m : measurements) {
    m.pose.head<3>() *= 10;
    m.legs *= 10;
  }
  EXPECT_THAT(CalibrateError(nominal, measurements), HasSubstr("is far outside the stroke [0, 3.5] cm"));
  EXPECT_THAT(CalibrateError(nominal, measurements), HasSubstr("readings look like mm, the robot"));
}

TEST(Calibration, RepeatedOrTranslatedPosesAreDegenerate) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const std::vector<Vector6d> one_pose(7, RandomFeasiblePoses(nominal, 1, 3)[0]);
  EXPECT_THAT(CalibrateError(nominal, Measure(truth, one_pose)), HasSubstr("degenerate pose set: leg 1"));
  EXPECT_THAT(CalibrateError(nominal, Measure(truth, one_pose)), HasSubstr("rank 1 of 7"));
  // One orientation: a and R b move together, 3 directions unseen.
  std::vector<Vector6d> translations;
  for (int j = 0; j < 12; ++j) {
    Vector6d v;
    v << Uniform(-2, 2), Uniform(-2, 2), Uniform(52.5, 54.5), 3, -2, 5;
    translations.push_back(v);
  }
  EXPECT_THAT(CalibrateError(nominal, Measure(truth, translations)), HasSubstr("rank 4 of 7"));
}

TEST(Calibration, NonFiniteInputAndBadOptionsAreErrors) {
  const Robot nominal = Preset("inria-left-hand");
  std::vector<Measurement> measurements = Measure(nominal, RandomFeasiblePoses(nominal, 8, 1));
  measurements[3].legs[1] = std::nan("");
  EXPECT_THAT(CalibrateError(nominal, measurements), HasSubstr("measurement 4: pose or leg readings are not finite"));
  measurements[3].legs[1] = 1;
  CalibrationOptions options;
  options.loss = RobustLoss::kHuber;
  options.loss_scale = 0;
  EXPECT_THAT(CalibrateError(nominal, measurements, options), HasSubstr("loss_scale: must be at least 1e-09, got 0"));
  options = {};
  options.weighted = true;
  options.noise = {0, 0, 0};
  EXPECT_THAT(CalibrateError(nominal, measurements, options), HasSubstr("at least one non-zero level"));
}

TEST(Calibration, AnUnfinishedSolveIsAnError) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  CalibrationOptions options;
  options.max_iterations = 1;
  const std::vector<Measurement> measurements = Measure(truth, RandomFeasiblePoses(nominal, 12, 4));
  EXPECT_THAT(CalibrateError(nominal, measurements, options),
              HasSubstr("did not converge (NO_CONVERGENCE after 1 iterations"));
  // A failed computation, not bad input (issue 37): the input was accepted.
  EXPECT_EQ(Calibrate(nominal, measurements, options).status().kind(), StatusKind::kFailed);
}

TEST(Calibration, CancelledBeforeOrDuringTheSolveReturnsCancelled) {
  const Robot nominal = Preset("inria-left-hand");
  const std::vector<Measurement> measurements =
      Measure(PerturbedRobot(nominal, 0.5), RandomFeasiblePoses(nominal, 12, 4));
  std::atomic<bool> cancel{true};
  StatusOr<CalibrationResult> result = Calibrate(nominal, measurements, {}, {nullptr, &cancel});
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(result.status().cancelled());
  // Cancelled by the first leg to finish: the others stop at their next iteration.
  cancel = false;
  CalibrationOptions options;
  options.num_threads = 1;
  int calls = 0;
  result = Calibrate(nominal, measurements, options,
                     {[&](int done, int total) {
                        ++calls;
                        EXPECT_EQ(total, kNumLegs);
                        cancel = done >= 1;
                      },
                      &cancel});
  EXPECT_TRUE(result.status().cancelled());
  EXPECT_GE(calls, 1);
}

TEST(Calibration, ProgressCountsTheLegs) {
  const Robot nominal = Preset("inria-left-hand");
  std::vector<int> seen;
  std::mutex mutex;
  StatusOr<CalibrationResult> result =
      Calibrate(nominal, Measure(nominal, RandomFeasiblePoses(nominal, 10, 4)), {}, {[&](int done, int total) {
                  std::lock_guard<std::mutex> lock(mutex);
                  seen.push_back(done);
                  EXPECT_EQ(total, kNumLegs);
                }});
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(seen, (std::vector<int>{1, 2, 3, 4, 5, 6}));
}

TEST(Calibration, ParsesLossNames) {
  for (RobustLoss loss : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    EXPECT_EQ(ParseRobustLoss(RobustLossName(loss)), loss);
  }
  EXPECT_FALSE(ParseRobustLoss("tukey").has_value());
  EXPECT_STREQ(ParameterName(6), "l");
}

}  // namespace
}  // namespace hexcal

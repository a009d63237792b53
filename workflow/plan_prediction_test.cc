// The predicted error against independent truth: the section 7 Monte Carlo
// study (core/simulation.h) for the parameters, and forward kinematics of
// robots drawn from the predicted covariance for the pose error.
#include "workflow/plan_prediction.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "core/forward_kinematics.h"
#include "core/simulation.h"
#include "tests/robot_presets.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::SpreadFeasiblePoses;

TEST(PlanPrediction, MeanErrorMatchesTheMonteCarloStudy) {
  const Robot robot = Preset("inria-left-hand");
  const std::vector<Vector6d> poses = SpreadFeasiblePoses(robot, 18, 11);
  for (bool weighted : {false, true}) {
    SimulationOptions options;
    options.runs = 400;
    options.seed = 3;
    options.calibration.weighted = weighted;
    options.calibration.noise = options.noise;
    StatusOr<SimulationResult> study = Simulate(robot, {FixedPoseSet("plan", poses)}, options);
    ASSERT_TRUE(study.ok()) << study.status().message();
    const PlanPrediction prediction = PredictPlanError(robot, poses, options.noise, weighted, {});
    ASSERT_TRUE(prediction.valid);
    // 400 runs x 42 parameters: the Monte Carlo mean is good to about 1 %.
    EXPECT_NEAR(prediction.mean_error, study->sets[0].mean, 0.06 * study->sets[0].mean) << "weighted " << weighted;
    EXPECT_NEAR(prediction.mean_sigma, prediction.mean_error / std::sqrt(2 / M_PI), 1e-12);
    EXPECT_GE(prediction.max_sigma, prediction.mean_sigma);
  }
}

// Robots drawn from N(nominal, C) and FK from the nominal readings: the RMS
// pose error over the draws is what the prediction says the parameters add.
TEST(PlanPrediction, PoseErrorMatchesForwardKinematicsOfDrawnRobots) {
  const Robot robot = Preset("inria-left-hand");
  const std::vector<Vector6d> poses = SpreadFeasiblePoses(robot, 18, 11);
  const std::vector<Vector6d> validation = ValidationPoses(robot);
  ASSERT_EQ(validation.size(), 200u);
  const NoiseModel noise{0.01, 0.1, 0.01};  // ten times the paper's: well above FK's tolerance
  const PlanPrediction prediction = PredictPlanError(robot, poses, noise, false, {validation.begin(), validation.begin() + 20});
  ASSERT_TRUE(prediction.valid);
  // The parameter covariance is block-diagonal; σ alone would lose the
  // correlations, so draw from each leg's full C_i, rebuilt here from the rows.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  double squared_position = 0;
  int samples = 0;
  for (int draw = 0; draw < 100; ++draw) {
    ParameterVector delta;
    for (int i = 0; i < kNumLegs; ++i) {
      InfoBlock information = InfoBlock::Zero(), scatter = InfoBlock::Zero();
      for (const Vector6d& v : poses) {
        const Pose pose = robot.PoseFromVector(v);
        const JacobianRow r = NominalJacobianRow(robot.legs[i], pose);
        const double reading = LegVector(robot.legs[i], pose).norm() - robot.legs[i].offset;
        const double sd = ResidualStdDev(robot, i, v, reading, noise);
        information += r.transpose() * r;
        scatter += sd * sd * r.transpose() * r;
      }
      const InfoBlock inverse = information.inverse();
      const InfoBlock covariance = inverse * scatter * inverse;
      const InfoBlock lower = Eigen::LLT<InfoBlock>(covariance).matrixL();
      Eigen::Matrix<double, kParamsPerLeg, 1> z;
      for (int k = 0; k < kParamsPerLeg; ++k) z[k] = normal(rng);
      delta.segment<kParamsPerLeg>(kParamsPerLeg * i) = lower * z;
    }
    const Robot drawn = WithParameters(robot, ParametersOf(robot) + delta);
    for (int k = 0; k < 20; ++k) {
      const Pose truth = robot.PoseFromVector(validation[k]);
      StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(drawn, InverseKinematics(robot, truth), truth);
      ASSERT_TRUE(fk.ok());
      squared_position += (fk->pose.position - truth.position).squaredNorm();
      ++samples;
    }
  }
  const double position_rms = std::sqrt(squared_position / samples);
  EXPECT_NEAR(prediction.from_parameters.position_rms, position_rms, 0.1 * position_rms);
  EXPECT_GT(prediction.heldout.position_rms, prediction.from_parameters.position_rms);
}

}  // namespace
}  // namespace hexcal::workflow

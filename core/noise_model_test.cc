// Noise model: the Euler partials and the residual gradient against central
// finite differences, and the variance formula against a Monte Carlo estimate.
#include "core/noise_model.h"

#include <gtest/gtest.h>

#include <random>

#include "core/identification.h"
#include "core/inverse_kinematics.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::Preset;
using ::hexcal::testing::Uniform;

TEST(NoiseModel, EulerPartialsMatchFiniteDifferences) {
  for (EulerConvention convention : {EulerConvention::kXYZ, EulerConvention::kZYX}) {
    const Eigen::Vector3d q(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
    const auto partials = RotationEulerPartials(q, convention);
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      Eigen::Vector3d qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      const Eigen::Matrix3d numeric =
          (RotationFromEuler(qp, convention) - RotationFromEuler(qm, convention)) / (2 * h);
      EXPECT_TRUE(MatrixNear(partials[k], numeric, 1e-9)) << "q" << k + 1;
    }
  }
}

TEST(NoiseModel, ResidualGradientMatchesFiniteDifferences) {
  const Robot robot = Preset("inria-left-hand");
  Vector6d v;
  v << 1, -0.5, 53.2, 3, -2, 10;
  const LegReadings readings = InverseKinematics(robot, robot.PoseFromVector(v));
  for (int leg = 0; leg < kNumLegs; ++leg) {
    const auto g = ResidualMeasurementGradient(robot, leg, v, readings[leg]);
    for (int k = 0; k < 7; ++k) {
      // Step 1e-4 in the robot unit, or 1e-4 rad = RadToDeg(1e-4) degrees for angles.
      const double h = 1e-4, step = k >= 3 && k < 6 ? RadToDeg(h) : h;
      Vector6d vp = v, vm = v;
      double lp = readings[leg], lm = readings[leg];
      if (k < 6) {
        vp[k] += step;
        vm[k] -= step;
      } else {
        lp += h;
        lm -= h;
      }
      const double fp = ImplicitResidual(robot.legs[leg], robot.PoseFromVector(vp), lp);
      const double fm = ImplicitResidual(robot.legs[leg], robot.PoseFromVector(vm), lm);
      EXPECT_NEAR(g[k], (fp - fm) / (2 * h), 1e-6 * (1 + std::abs(g[k]))) << "leg " << leg << " k " << k;
    }
  }
}

TEST(NoiseModel, StdDevMatchesMonteCarlo) {
  const Robot robot = Preset("inria-left-hand");
  NoiseModel noise;
  noise.position = 0.01;
  noise.angle_deg = 0.05;
  noise.leg = 0.02;
  Vector6d v;
  v << -1, 2, 53.8, -4, 1, 20;
  const LegReadings readings = InverseKinematics(robot, robot.PoseFromVector(v));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  const int samples = 200000;
  for (int leg : {0, 3}) {
    double sum = 0, sum2 = 0;
    for (int s = 0; s < samples; ++s) {
      Vector6d noisy = v;
      for (int k = 0; k < 3; ++k) noisy[k] += noise.position * unit(rng);
      for (int k = 3; k < 6; ++k) noisy[k] += noise.angle_deg * unit(rng);
      const double f =
          ImplicitResidual(robot.legs[leg], robot.PoseFromVector(noisy), readings[leg] + noise.leg * unit(rng));
      sum += f;
      sum2 += f * f;
    }
    const double mean = sum / samples, sd = std::sqrt(sum2 / samples - mean * mean);
    EXPECT_NEAR(ResidualStdDev(robot, leg, v, readings[leg], noise), sd, 0.01 * sd) << "leg " << leg;
  }
}

TEST(NoiseModel, RejectsNegativeAndNonFiniteLevels) {
  NoiseModel noise;
  std::string error;
  EXPECT_TRUE(noise.IsValid(&error));
  noise.leg = -1;
  EXPECT_FALSE(noise.IsValid(&error));
  noise.leg = std::nan("");
  EXPECT_FALSE(noise.IsValid(&error));
}

TEST(NoiseModel, PoseCovarianceOfTheModelGivesTheModelsStdDev) {
  const Robot robot = Preset("inria-left-hand");
  const Vector6d pose = (Vector6d() << 1, -2, 52, 5, -3, 10).finished();
  NoiseModel noise;
  noise.position = 0.003;
  noise.angle_deg = 0.02;
  noise.leg = 0.002;
  Vector6d variances;
  const double sp = noise.PositionStdDev(), sq = RadToDeg(noise.AngleStdDevRad());
  variances << sp * sp, sp * sp, sp * sp, sq * sq, sq * sq, sq * sq;
  for (int leg = 0; leg < kNumLegs; ++leg) {
    const double reading = InverseKinematics(robot, robot.PoseFromVector(pose))[leg];
    EXPECT_NEAR(ResidualStdDev(robot, leg, pose, reading, noise, variances.asDiagonal()),
                ResidualStdDev(robot, leg, pose, reading, noise), 1e-12);
  }
}

}  // namespace
}  // namespace hexcal

// The implicit calibration model, its identification Jacobian, the information
// blocks and the observability indices, against finite differences, an
// explicitly assembled J_P and its SVD, and the length scaling of the indices.
#include "core/identification.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/observability.h"
#include "core/robot_io.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::Uniform;

using ::hexcal::testing::Preset;

// Random poses in the working range of each preset.
Pose RandomInriaPose(const Robot& robot) {
  Vector6d v;
  v << Uniform(-3, 3), Uniform(-3, 3), Uniform(52, 55), Uniform(-10, 10), Uniform(-10, 10), Uniform(-10, 10);
  return robot.PoseFromVector(v);
}

Pose RandomDeltalabPose(const Robot& robot) {
  Vector6d v;
  v << Uniform(-40, 40), Uniform(-40, 40), Uniform(380, 430), Uniform(-8, 8), Uniform(-8, 8), Uniform(-8, 8);
  return robot.PoseFromVector(v);
}

std::vector<Pose> RandomInriaPoses(const Robot& robot, int count) {
  std::vector<Pose> poses;
  for (int k = 0; k < count; ++k) poses.push_back(RandomInriaPose(robot));
  return poses;
}

Leg WithLegParameters(Leg leg, const LegParameters& p) {
  leg.a_in_base = p.head<3>();
  leg.b_in_platform = p.segment<3>(3);
  leg.offset = p[6];
  return leg;
}

// J_P assembled row by row: row (6 j + i) holds leg i's implicit row at pose j in columns 7i..7i+6.
Eigen::MatrixXd AssembleJacobian(const Robot& robot, const std::vector<Pose>& poses) {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(kNumLegs * poses.size(), kNumParams);
  const std::vector<Pose>::size_type n = poses.size();
  for (std::vector<Pose>::size_type j = 0; j < n; ++j) {
    const LegReadings readings = InverseKinematics(robot, poses[j]);
    for (int i = 0; i < kNumLegs; ++i) {
      jacobian.block<1, kParamsPerLeg>(kNumLegs * j + i, kParamsPerLeg * i) =
          ImplicitJacobianRow(robot.legs[i], poses[j], readings[i]);
    }
  }
  return jacobian;
}

// F_ij = |P + R b - a|² - (L + l)² vanishes at the readings inverse kinematics gives.
TEST(Identification, ResidualVanishesAtIkReadings) {
  for (const std::string name : {"inria-left-hand", "deltalab-table"}) {
    const Robot robot = Preset(name);
    for (int trial = 0; trial < 50; ++trial) {
      const Pose pose = name == "inria-left-hand" ? RandomInriaPose(robot) : RandomDeltalabPose(robot);
      const LegReadings readings = InverseKinematics(robot, pose);
      for (int i = 0; i < kNumLegs; ++i) {
        const double length = readings[i] + robot.legs[i].offset;
        EXPECT_NEAR(ImplicitResidual(robot.legs[i], pose, readings[i]), 0.0, 1e-14 * length * length);
        // Off the IK reading by 0.1: F = |v|² - (|v| + 0.1)² = -0.2 |v| - 0.01.
        EXPECT_NEAR(ImplicitResidual(robot.legs[i], pose, readings[i] + 0.1), -0.2 * length - 0.01,
                    1e-12 * length * length);
      }
    }
  }
}

// dF/d(a, b, l) against central differences in each of the 7 leg parameters, at a reading
// that need not match the pose.
TEST(Identification, ImplicitRowMatchesFiniteDifferences) {
  const Robot robot = Preset("inria-left-hand");
  for (int trial = 0; trial < 50; ++trial) {
    const Pose pose = RandomInriaPose(robot);
    const int i = trial % kNumLegs;
    const Leg& leg = robot.legs[i];
    const double reading = Uniform(0, 3.5);
    const JacobianRow analytic = ImplicitJacobianRow(leg, pose, reading);
    JacobianRow numeric;
    const double h = 1e-4;
    for (int k = 0; k < kParamsPerLeg; ++k) {
      const LegParameters step = LegParameters::Unit(k) * h;
      numeric[k] = (ImplicitResidual(WithLegParameters(leg, LegParametersOf(leg) + step), pose, reading) -
                    ImplicitResidual(WithLegParameters(leg, LegParametersOf(leg) - step), pose, reading)) /
                   (2 * h);
    }
    // F is quadratic in the parameters: central differences are exact up to round-off.
    EXPECT_TRUE(MatrixNear(analytic, numeric, 1e-8)) << "leg " << i + 1;
  }
}

// The planner's row (L + l = |v|) equals the implicit row at the IK reading.
TEST(Identification, NominalRowIsImplicitRowAtIkReading) {
  const Robot robot = Preset("deltalab-table");
  for (int trial = 0; trial < 50; ++trial) {
    const Pose pose = RandomDeltalabPose(robot);
    const LegReadings readings = InverseKinematics(robot, pose);
    for (int i = 0; i < kNumLegs; ++i) {
      EXPECT_TRUE(MatrixNear(NominalJacobianRow(robot.legs[i], pose),
                             ImplicitJacobianRow(robot.legs[i], pose, readings[i]), 1e-11));
    }
  }
}

// M_i = J_Piᵀ J_Pi from the explicit J_P; adding then removing a pose restores the blocks.
TEST(Identification, InformationBlocksAddAndRemove) {
  const Robot robot = Preset("inria-left-hand");
  const std::vector<Pose> poses = RandomInriaPoses(robot, 12);
  InformationBlocks info = ComputeInformation(robot, poses);
  EXPECT_EQ(info.num_poses, 12);
  const Eigen::MatrixXd jacobian = AssembleJacobian(robot, poses);
  const Eigen::MatrixXd normal = jacobian.transpose() * jacobian;
  for (int i = 0; i < kNumLegs; ++i) {
    const InfoBlock& block = info.blocks[i];
    EXPECT_TRUE(MatrixNear(block, normal.block<7, 7>(7 * i, 7 * i), 1e-9 * normal.norm())) << "leg " << i + 1;
    EXPECT_TRUE(MatrixNear(block, block.transpose(), 0.0));
    const double smallest = Eigen::SelfAdjointEigenSolver<InfoBlock>(block).eigenvalues()[0];
    EXPECT_GE(smallest, -1e-12 * block.norm()) << "leg " << i + 1;
  }
  const InformationBlocks before = info;
  const Pose extra = RandomInriaPose(robot);
  info.AddPose(robot, extra);
  EXPECT_EQ(info.num_poses, 13);
  EXPECT_GT((info.blocks[0] - before.blocks[0]).norm(), 1.0);
  info.RemovePose(robot, extra);
  EXPECT_EQ(info.num_poses, 12);
  for (int i = 0; i < kNumLegs; ++i) {
    EXPECT_TRUE(MatrixNear(info.blocks[i], before.blocks[i], 1e-9 * before.blocks[i].norm())) << "leg " << i + 1;
  }
}

// The 42 singular values are those of the explicit 6N x 42 block-diagonal J_P (JacobiSVD),
// and O1..O4 follow from them by the formulas of observability.h.
TEST(Observability, SingularValuesAndIndicesFromExplicitSvd) {
  const Robot robot = Preset("inria-left-hand");
  const std::vector<Pose> poses = RandomInriaPoses(robot, 18);
  const Eigen::MatrixXd jacobian = AssembleJacobian(robot, poses);
  ASSERT_EQ(jacobian.rows(), 108);
  const Eigen::VectorXd expected = Eigen::JacobiSVD<Eigen::MatrixXd>(jacobian).singularValues();
  const InformationBlocks info = ComputeInformation(robot, poses);
  const SingularValues sigma = SingularValuesOf(info);
  EXPECT_TRUE(MatrixNear(sigma, expected, 1e-9 * expected[0]));
  EXPECT_GT(expected[kNumParams - 1], 1e-6 * expected[0]);  // full rank, or the indices say little

  const double sigma_max = expected[0], sigma_min = expected[kNumParams - 1];
  const double geometric_mean = std::exp(expected.array().log().mean());
  // σ from eig(J_Pᵀ J_P) squares the condition number: σ_min is good to about
  // eps·(σ_max/σ_min)² relative, not eps (here about 1e-9).
  const double condition = sigma_max / sigma_min;
  const double tolerance = 1e-12 + 10 * std::numeric_limits<double>::epsilon() * condition * condition;
  const ObservabilityIndices o = ComputeIndices(info);
  EXPECT_EQ(o.num_poses, 18);
  EXPECT_NEAR(o.o1, geometric_mean / std::sqrt(18.0), 1e-9 * o.o1);
  EXPECT_NEAR(o.o2, sigma_min / sigma_max, tolerance * o.o2);
  EXPECT_NEAR(o.o3, sigma_min, tolerance * o.o3);
  EXPECT_NEAR(o.o4, sigma_min * sigma_min / sigma_max, 2 * tolerance * o.o4);
  EXPECT_NEAR(o.sigma_max, sigma_max, 1e-9 * sigma_max);
  // The pose-list overload agrees.
  EXPECT_DOUBLE_EQ(ComputeIndices(robot, poses).o1, o.o1);
}

// Every row of J_P is linear in length, so in mm instead of cm (x10) every σ is x10:
// O1, O3, O4 scale by 10 and O2, the inverse condition number, is unchanged.
TEST(Observability, ScalingWithLengthUnit) {
  const Robot robot_cm = Preset("inria-left-hand");
  Robot robot_mm = robot_cm;
  robot_mm.length_unit = LengthUnit::kMillimetre;
  for (Leg& leg : robot_mm.legs) {
    leg.a_in_base *= 10;
    leg.b_in_platform *= 10;
    leg.offset *= 10;
    leg.stroke_min *= 10;
    leg.stroke_max *= 10;
  }
  const std::vector<Pose> poses_cm = RandomInriaPoses(robot_cm, 20);
  std::vector<Pose> poses_mm = poses_cm;
  for (Pose& pose : poses_mm) pose.position *= 10;
  const ObservabilityIndices cm = ComputeIndices(robot_cm, poses_cm);
  const ObservabilityIndices mm = ComputeIndices(robot_mm, poses_mm);
  EXPECT_NEAR(mm.o2, cm.o2, 1e-8 * cm.o2);
  EXPECT_NEAR(mm.o1, 10 * cm.o1, 1e-8 * mm.o1);
  EXPECT_NEAR(mm.o3, 10 * cm.o3, 1e-8 * mm.o3);
  EXPECT_NEAR(mm.o4, 10 * cm.o4, 1e-8 * mm.o4);
  EXPECT_GT(cm.o3, 0);
}

// With fewer than 7 poses each 7x7 block has rank < 7, so σ_min = 0 and O1 = O3 = O4 = 0,
// exactly: round-off must not turn the zero singular value into a small positive one
// (before the rank tolerance in SingularValuesOf, 6 random poses gave O3 > 0 in ~1.5% of sets).
TEST(Observability, FewerThanSevenPosesIsRankDeficient) {
  const Robot robot = Preset("inria-left-hand");
  for (int count = 0; count < kParamsPerLeg; ++count) {
    for (int trial = 0; trial < (count == 6 ? 2000 : 50); ++trial) {
      const ObservabilityIndices o = ComputeIndices(robot, RandomInriaPoses(robot, count));
      ASSERT_EQ(o.num_poses, count);
      ASSERT_EQ(o.o3, 0.0) << count << " poses, trial " << trial;
      ASSERT_EQ(o.o1, 0.0) << count << " poses, trial " << trial;
      ASSERT_EQ(o.o4, 0.0) << count << " poses, trial " << trial;
    }
  }
  // Six distinct poses measured twice are still rank-deficient.
  std::vector<Pose> repeated = RandomInriaPoses(robot, 6);
  repeated.insert(repeated.end(), repeated.begin(), repeated.end());
  EXPECT_EQ(ComputeIndices(robot, repeated).o3, 0.0);
  // Seven poses in general position are enough.
  EXPECT_GT(ComputeIndices(robot, RandomInriaPoses(robot, kParamsPerLeg)).o3, 0.0);
}

}  // namespace
}  // namespace hexcal

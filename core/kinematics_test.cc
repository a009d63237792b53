// Inverse kinematics, its Jacobian, local forward kinematics and the workspace
// constraints, each against an independent truth.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/constraints.h"
#include "core/forward_kinematics.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::Uniform;

using ::hexcal::testing::Preset;

// A random pose around a robot's nominal workspace: [x, y, z, q1, q2, q3] ranges per preset.
struct PoseRange {
  double xy, z_min, z_max, angle_deg;
};
PoseRange RangeOf(const std::string& preset) {
  return preset == "inria-left-hand" ? PoseRange{2, 52.5, 54.5, 5} : PoseRange{40, 380, 430, 8};
}
Pose RandomPose(const Robot& robot, const PoseRange& r) {
  Vector6d v;
  v << Uniform(-r.xy, r.xy), Uniform(-r.xy, r.xy), Uniform(r.z_min, r.z_max), Uniform(-r.angle_deg, r.angle_deg),
      Uniform(-r.angle_deg, r.angle_deg), Uniform(-r.angle_deg, r.angle_deg);
  return robot.PoseFromVector(v);
}

// Readings by hand: INRIA leg 1 at the untilted pose P = (0, 0, 50):
// v = P + b - a = (-3 + 9.7, 7.3 - 9.1, 50) = (6.7, -1.8, 50), L = |v| - 52.2496.
TEST(InverseKinematics, HandComputedUntiltedPose) {
  const Robot robot = Preset("inria-left-hand");
  Pose pose;
  pose.position = Eigen::Vector3d(0, 0, 50);
  const LegReadings readings = InverseKinematics(robot, pose);
  EXPECT_NEAR(readings[0], std::sqrt(6.7 * 6.7 + 1.8 * 1.8 + 2500.0) - 52.2496, 1e-12);
  // Leg 3: v = (7.822 - 12.76, -1.052 - 3.9, 50), l = 52.2568.
  EXPECT_NEAR(readings[2], std::sqrt(4.938 * 4.938 + 4.952 * 4.952 + 2500.0) - 52.2568, 1e-12);
}

// Readings = |P + R b - a| - l with the preset's table typed in, at a tilted pose.
TEST(InverseKinematics, MatchesFormulaWithTypedInParameters) {
  const Robot robot = Preset("inria-left-hand");
  const double a[6][3] = {{-9.7, 9.1, 0}, {9.7, 9.1, 0}, {12.76, 3.9, 0}, {3, -13, 0}, {-3, -13, 0}, {-12.76, 3.9, 0}};
  const double b[6][3] = {{-3, 7.3, 0},       {3, 7.3, 0},         {7.822, -1.052, 0},
                          {4.822, -6.248, 0}, {-4.822, -6.248, 0}, {-7.822, -1.052, 0}};
  const double l[6] = {52.2496, 52.2496, 52.2568, 52.2568, 52.2568, 52.2568};
  Pose pose;
  pose.position = Eigen::Vector3d(1.2, -0.7, 53.1);
  pose.rotation = Eigen::AngleAxisd(0.07, Eigen::Vector3d(1, 2, -0.5).normalized()).matrix();
  const LegReadings readings = InverseKinematics(robot, pose);
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::Vector3d v = pose.position + pose.rotation * Eigen::Vector3d(b[i][0], b[i][1], b[i][2]) -
                              Eigen::Vector3d(a[i][0], a[i][1], a[i][2]);
    EXPECT_NEAR(readings[i], v.norm() - l[i], 1e-12) << "leg " << i + 1;
  }
}

// dL/d[P, theta] against central differences through ApplyIncrement.
TEST(InverseKinematics, JacobianMatchesFiniteDifferences) {
  for (const std::string name : {"inria-left-hand", "deltalab-table"}) {
    const Robot robot = Preset(name);
    const PoseRange range = RangeOf(name);
    for (int trial = 0; trial < 50; ++trial) {
      const Pose pose = RandomPose(robot, range);
      const Eigen::Matrix<double, 6, 6> analytic = InverseKinematicsJacobian(robot, pose);
      Eigen::Matrix<double, 6, 6> numeric;
      for (int k = 0; k < 6; ++k) {
        const double h = k < 3 ? 1e-6 * range.z_max : 1e-6;
        const Vector6d step = Vector6d::Unit(k) * h;
        numeric.col(k) = (InverseKinematics(robot, ApplyIncrement(pose, step)) -
                          InverseKinematics(robot, ApplyIncrement(pose, -step))) /
                         (2 * h);
      }
      EXPECT_TRUE(MatrixNear(analytic.leftCols<3>(), numeric.leftCols<3>(), 1e-7)) << name;
      EXPECT_TRUE(MatrixNear(analytic.rightCols<3>(), numeric.rightCols<3>(), 1e-8 * range.z_max)) << name;
    }
  }
}

// ApplyIncrement: P += dP and R <- exp([theta]x) R, checked on a rotation about z.
TEST(ForwardKinematics, ApplyIncrementIsLeftRotation) {
  Pose pose;
  pose.position = Eigen::Vector3d(1, 2, 3);
  pose.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).matrix();
  Vector6d increment;
  increment << 0.5, 0, -1, 0, 0, 0.2;
  const Pose moved = ApplyIncrement(pose, increment);
  EXPECT_TRUE(MatrixNear(moved.position, Eigen::Vector3d(1.5, 2, 2), 1e-15));
  EXPECT_TRUE(
      MatrixNear(moved.rotation, Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).matrix() * pose.rotation, 1e-15));
}

// IK then local FK from a perturbed start gives the pose back, on 200 poses per preset.
TEST(ForwardKinematics, LocalRoundTrip) {
  for (const std::string name : {"inria-left-hand", "deltalab-table"}) {
    const Robot robot = Preset(name);
    const PoseRange range = RangeOf(name);
    double worst_position = 0, worst_angle = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const Pose truth = RandomPose(robot, range);
      Vector6d perturbation;
      perturbation << Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1), Uniform(-0.03, 0.03), Uniform(-0.03, 0.03),
          Uniform(-0.03, 0.03);
      perturbation.head<3>() *= 0.01 * range.z_max;
      const Pose start = ApplyIncrement(truth, perturbation);
      StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(robot, InverseKinematics(robot, truth), start);
      ASSERT_TRUE(fk.ok()) << name << " trial " << trial << ": " << fk.status().message();
      worst_position = std::max(worst_position, (fk->pose.position - truth.position).norm() / truth.position.norm());
      worst_angle = std::max(worst_angle, RotationDistance(fk->pose.rotation, truth.rotation));
    }
    EXPECT_LT(worst_position, 1e-9) << name;
    EXPECT_LT(worst_angle, 1e-9) << name;
  }
}

// Readings no pose can reach come back as an error: legs 1-3 at 52 cm and legs 4-6
// at 1052 cm violate |a4 - b4| <= |a4 - a1| + |a1 - b1| + |b1 - b4| (about 23 + 52 + 14).
TEST(ForwardKinematics, LocalFailsOnUnreachableReadings) {
  const Robot robot = Preset("inria-left-hand");
  const Pose start = robot.PoseFromVector((Vector6d() << 0, 0, 53.5, 0, 0, 0).finished());
  LegReadings readings;
  readings << 0, 0, 0, 1000, 1000, 1000;
  StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(robot, readings, start);
  ASSERT_FALSE(fk.ok());
  EXPECT_THAT(fk.status().message(), ::testing::HasSubstr("did not converge"));
  readings.setConstant(std::nan(""));
  EXPECT_FALSE(ForwardKinematicsLocal(robot, readings, start).ok());
}

// A robot whose legs are all vertical (b_i straight above a_i) is singular
// everywhere: the readings fix z, q1, q2 but not x, y, q3. Local FK meets the
// readings from any start, and must say the pose is not determined rather than
// return the start's x, y, q3 as if they had been measured.
TEST(ForwardKinematics, LocalFailsAtASingularity) {
  Robot robot = Preset("inria-left-hand");
  for (Leg& leg : robot.legs) leg.b_in_platform = leg.a_in_base;
  const Pose truth = robot.PoseFromVector((Vector6d() << 0, 0, 53.5, 0, 0, 0).finished());
  const Pose start = robot.PoseFromVector((Vector6d() << 0.5, -0.3, 53, 1, -1, 2).finished());
  StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(robot, InverseKinematics(robot, truth), start);
  ASSERT_FALSE(fk.ok());
  EXPECT_THAT(fk.status().message(), ::testing::HasSubstr("the pose is at a singularity"));
  // The INRIA robot itself is well conditioned at the same pose.
  const Robot inria = Preset("inria-left-hand");
  StatusOr<LocalFkResult> regular = ForwardKinematicsLocal(inria, InverseKinematics(inria, truth), start);
  ASSERT_TRUE(regular.ok()) << regular.status().message();
  EXPECT_GT(regular->condition_ratio, 1e-3);
}

// The middle of the INRIA workspace is feasible; the report's verdict is its smallest margin.
TEST(Constraints, MiddleOfWorkspaceIsFeasible) {
  const Robot robot = Preset("inria-left-hand");
  const Pose middle = robot.PoseFromVector((Vector6d() << 0, 0, 53.5, 0, 0, 0).finished());
  const ConstraintReport report = EvaluateConstraints(robot, middle);
  EXPECT_TRUE(report.feasible) << report.worst_label << " " << report.worst_margin;
  EXPECT_GT(report.worst_margin, 0);
  EXPECT_TRUE(IsFeasible(robot, middle));
}

// IsFeasible agrees with EvaluateConstraints, whose verdict and worst margin follow its margins.
TEST(Constraints, IsFeasibleAgreesWithReport) {
  const Robot robot = Preset("inria-left-hand");
  int feasible_count = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Vector6d v;
    v << Uniform(-3, 3), Uniform(-3, 3), Uniform(51, 56), Uniform(-8, 8), Uniform(-8, 8), Uniform(-8, 8);
    const Pose pose = robot.PoseFromVector(v);
    const ConstraintReport report = EvaluateConstraints(robot, pose);
    ASSERT_EQ(IsFeasible(robot, pose), report.feasible) << v.transpose();
    const auto worst = std::min_element(report.margins.begin(), report.margins.end(),
                                        [](const auto& p, const auto& q) { return p.margin < q.margin; });
    ASSERT_NE(worst, report.margins.end());
    EXPECT_EQ(report.worst_margin, worst->margin);
    EXPECT_EQ(report.feasible, worst->margin >= -kFeasibilityTolerance);
    feasible_count += report.feasible;
  }
  // Both verdicts occur, or the agreement says little.
  EXPECT_GT(feasible_count, 20);
  EXPECT_LT(feasible_count, 480);
}

double MarginOf(const ConstraintReport& report, const std::string& label) {
  for (const ConstraintMargin& m : report.margins) {
    if (m.label == label) return m.margin;
  }
  ADD_FAILURE() << "no constraint labelled '" << label << "'";
  return std::nan("");
}

// Stroke margins are stroke_max - L_i and L_i - stroke_min under the labels "stroke max L<i>"
// and "stroke min L<i>"; a platform too low or too high is reported as a stroke violation.
TEST(Constraints, StrokeViolationsAreLabelled) {
  const Robot robot = Preset("inria-left-hand");
  // z = 49: every L_i is about -3 (< 0); z = 58: about 6 (> 3.5).
  for (const double z : {49.0, 58.0}) {
    const Pose pose = robot.PoseFromVector((Vector6d() << 0, 0, z, 0, 0, 0).finished());
    const LegReadings readings = InverseKinematics(robot, pose);
    const ConstraintReport report = EvaluateConstraints(robot, pose);
    EXPECT_FALSE(report.feasible);
    EXPECT_THAT(report.worst_label, ::testing::StartsWith(z < 53 ? "stroke min L" : "stroke max L"));
    for (int i = 0; i < kNumLegs; ++i) {
      const std::string leg = std::to_string(i + 1);
      EXPECT_NEAR(MarginOf(report, "stroke min L" + leg), readings[i] - 0.0, 1e-12);
      EXPECT_NEAR(MarginOf(report, "stroke max L" + leg), 3.5 - readings[i], 1e-12);
      EXPECT_LT(z < 53 ? MarginOf(report, "stroke min L" + leg) : MarginOf(report, "stroke max L" + leg), 0);
    }
  }
}

// A pose exactly on a stroke limit is feasible despite round-off, and one just outside is not:
// at P = (0, 0, z) with z² = 52.2496² - (6.7² + 1.8²), legs 1 and 2 read exactly stroke_min = 0.
TEST(Constraints, StrokeLimitWithinTolerance) {
  const Robot robot = Preset("inria-left-hand");
  const double z_at_min = std::sqrt(52.2496 * 52.2496 - (6.7 * 6.7 + 1.8 * 1.8));
  for (const double dz : {0.0, 1e-12, -1e-12}) {
    Pose pose;
    pose.position = Eigen::Vector3d(0, 0, z_at_min + dz);
    EXPECT_TRUE(IsFeasible(robot, pose)) << dz;
    EXPECT_TRUE(EvaluateConstraints(robot, pose).feasible) << dz;
  }
  Pose below;
  below.position = Eigen::Vector3d(0, 0, z_at_min - 1e-6);
  const ConstraintReport report = EvaluateConstraints(robot, below);
  EXPECT_FALSE(report.feasible);
  EXPECT_FALSE(IsFeasible(robot, below));
  EXPECT_THAT(report.worst_label, ::testing::AnyOf("stroke min L1", "stroke min L2"));
  // dL/dz = z / |v| with |v| = 52.2496.
  EXPECT_NEAR(report.worst_margin, -1e-6 * z_at_min / 52.2496, 1e-12);
}

// det J_IK from central differences of the readings: a truth independent of
// InverseKinematicsJacobian.
double DeterminantByDifferences(const Robot& robot, const Pose& pose) {
  Eigen::Matrix<double, kNumLegs, 6> j;
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    const Vector6d step = Vector6d::Unit(k) * h;
    j.col(k) = (InverseKinematics(robot, ApplyIncrement(pose, step)) -
                InverseKinematics(robot, ApplyIncrement(pose, -step))) / (2 * h);
  }
  return j.determinant();
}

// Section 5.3's assembly mode. Without its yaw bound, the INRIA preset's
// boundary set gains poses on the far side of a singularity; the mode's margin
// is det J_IK over its value at the home pose less min_det_ratio, and it keeps
// exactly the boundary poses on the home side: the paper's 44 again.
TEST(Constraints, AssemblyModeKeepsTheHomeSideOfTheSingularities) {
  Robot robot = Preset("inria-left-hand");
  ASSERT_TRUE(robot.limits.assembly_mode && robot.limits.pose_box);
  robot.limits.pose_box->bounds[5].reset();
  Robot any_mode = robot;
  any_mode.limits.assembly_mode.reset();
  CandidateOptions options;
  options.kind = CandidateKind::kBoundary;
  const StatusOr<CandidateSet> all = GenerateCandidates(any_mode, options);
  const StatusOr<CandidateSet> kept = GenerateCandidates(robot, options);
  ASSERT_TRUE(all.ok() && kept.ok());

  const AssemblyMode& mode = *robot.limits.assembly_mode;
  const double home = DeterminantByDifferences(robot, robot.PoseFromVector(mode.pose));
  size_t on_home_side = 0;
  for (const Vector6d& v : all->poses) {
    const Pose pose = robot.PoseFromVector(v);
    const double ratio = DeterminantByDifferences(robot, pose) / home;
    const ConstraintReport report = EvaluateConstraints(robot, pose);
    EXPECT_NEAR(MarginOf(report, "assembly mode"), ratio - mode.min_det_ratio, 1e-6) << v.transpose();
    if (ratio >= mode.min_det_ratio) {
      ++on_home_side;
    } else {
      EXPECT_EQ(report.worst_label, "assembly mode") << v.transpose();
      EXPECT_FALSE(IsFeasible(robot, pose));
    }
  }
  EXPECT_EQ(kept->poses.size(), on_home_side);
  EXPECT_EQ(on_home_side, 44u);
  EXPECT_GT(all->poses.size(), 44u);
}

// Shortest distance between segments, cases worked by hand.
TEST(SegmentDistance, HandCases) {
  using V = Eigen::Vector3d;
  // Parallel, overlapping: the gap between the lines.
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)), 1.0, 1e-15);
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(4, 0, 0), V(3, 2, 0), V(1, 2, 0)), 2.0, 1e-15);
  // Parallel, disjoint along the axis: endpoint (1,0,0) to endpoint (2,1,0).
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(1, 0, 0), V(2, 1, 0), V(3, 1, 0)), std::sqrt(2.0), 1e-15);
  // Parallel along an oblique direction (non-exact arithmetic): gap 0.5 along the normal n.
  const V d = V(0.3, -1.7, 2.9).normalized(), n = d.cross(V(1, 0, 0)).normalized();
  EXPECT_NEAR(SegmentDistance(V(1, 2, 3), V(1, 2, 3) + 3 * d, V(1, 2, 3) + d + 0.5 * n, V(1, 2, 3) + 5 * d + 0.5 * n),
              0.5, 1e-12);
  // Collinear and overlapping: touching.
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(2, 0, 0), V(1, 0, 0), V(3, 0, 0)), 0.0, 1e-15);
  // Crossing in a plane, and skew crossing 2 apart.
  EXPECT_NEAR(SegmentDistance(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 0), V(0, 1, 0)), 0.0, 1e-15);
  EXPECT_NEAR(SegmentDistance(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 2), V(0, 1, 2)), 2.0, 1e-15);
  // The lines cross, the segments do not: endpoint (1,0,0) to interior point (2,0,1).
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(1, 0, 0), V(2, -1, 1), V(2, 1, 1)), std::sqrt(2.0), 1e-15);
  // Endpoint to endpoint: (1,0,0) to (1,1,1) on a skew segment going away.
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(1, 0, 0), V(1, 1, 1), V(1, 3, 5)), std::sqrt(2.0), 1e-15);
  // Degenerate: point-point, point-segment (interior and beyond the end), both orders.
  EXPECT_NEAR(SegmentDistance(V(1, 2, 3), V(1, 2, 3), V(4, 6, 3), V(4, 6, 3)), 5.0, 1e-15);
  EXPECT_NEAR(SegmentDistance(V(0.5, 2, 0), V(0.5, 2, 0), V(0, 0, 0), V(1, 0, 0)), 2.0, 1e-15);
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(1, 0, 0), V(0.5, 2, 0), V(0.5, 2, 0)), 2.0, 1e-15);
  EXPECT_NEAR(SegmentDistance(V(3, 0, 4), V(3, 0, 4), V(0, 0, 0), V(1, 0, 0)), std::sqrt(20.0), 1e-15);
  EXPECT_NEAR(SegmentDistance(V(0, 0, 0), V(1, 0, 0), V(-3, 0, 4), V(-3, 0, 4)), 5.0, 1e-15);
}

// Against a ternary search: the distance from p(s) to segment q is convex in s.
TEST(SegmentDistance, MatchesConvexMinimisation) {
  auto point_to_segment = [](const Eigen::Vector3d& x, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
    const Eigen::Vector3d d = q1 - q0;
    const double t = std::clamp((x - q0).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (q0 + t * d - x).norm();
  };
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::Vector3d p[2], q[2];
    for (auto* x : {&p[0], &p[1], &q[0], &q[1]}) *x = Eigen::Vector3d(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
    double lo = 0, hi = 1;
    auto f = [&](double s) { return point_to_segment(p[0] + s * (p[1] - p[0]), q[0], q[1]); };
    for (int it = 0; it < 200; ++it) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if (f(m1) < f(m2)) {
        hi = m2;
      } else {
        lo = m1;
      }
    }
    EXPECT_NEAR(SegmentDistance(p[0], p[1], q[0], q[1]), f(0.5 * (lo + hi)), 1e-9);
  }
}

}  // namespace
}  // namespace hexcal

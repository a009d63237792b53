// Candidate measurement poses: every candidate must satisfy the robot's
// limits, be reproducible from its seed, and (boundary) have every leg at a
// stroke end; impossible requests must fail with a message naming the robot.
#include "core/candidates.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

#include "core/constraints.h"
#include "core/forward_kinematics.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::testing::HasSubstr;

using ::hexcal::testing::Preset;

CandidateSet Generate(const Robot& robot, CandidateKind kind, int count, uint64_t seed) {
  CandidateOptions options;
  options.kind = kind;
  options.count = count;
  options.seed = seed;
  StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
  EXPECT_TRUE(set.ok()) << set.status().message();
  return set.ok() ? *set : CandidateSet{};
}

// Random and Halton candidates: the requested count, each inside the pose box and feasible.
TEST(Candidates, RandomAndUniformAreFeasibleAndInsideTheBox) {
  const Robot robot = Preset("inria-left-hand");
  const PoseBox& box = *robot.limits.pose_box;
  for (CandidateKind kind : {CandidateKind::kRandom, CandidateKind::kUniform}) {
    const CandidateSet set = Generate(robot, kind, 200, 1);
    ASSERT_EQ(set.poses.size(), 200u) << CandidateKindName(kind);
    EXPECT_GE(set.draws, 200);
    for (const Vector6d& v : set.poses) {
      for (int k = 0; k < 6; ++k) {
        EXPECT_TRUE(box.bounds[k]->Contains(v[k])) << CandidateKindName(kind) << " coordinate " << k << ": " << v[k];
      }
      const ConstraintReport report = EvaluateConstraints(robot, robot.PoseFromVector(v));
      EXPECT_TRUE(report.feasible) << CandidateKindName(kind) << " " << v.transpose() << ": " << report.worst_label;
    }
  }
}

// The same seed gives the same poses; another seed gives other poses.
TEST(Candidates, SeedDeterminesThePoses) {
  const Robot robot = Preset("inria-left-hand");
  for (CandidateKind kind : {CandidateKind::kRandom, CandidateKind::kUniform}) {
    const CandidateSet first = Generate(robot, kind, 50, 7);
    const CandidateSet again = Generate(robot, kind, 50, 7);
    const CandidateSet other = Generate(robot, kind, 50, 8);
    ASSERT_EQ(first.poses.size(), 50u);
    ASSERT_EQ(other.poses.size(), 50u);
    EXPECT_EQ(first.poses, again.poses) << CandidateKindName(kind);
    EXPECT_EQ(first.draws, again.draws);
    int shared = 0;
    for (const Vector6d& v : first.poses) shared += std::count(other.poses.begin(), other.poses.end(), v);
    EXPECT_EQ(shared, 0) << CandidateKindName(kind);
  }
}

// A pose box no feasible pose can be drawn from (z in [0, 1], legs are 52 cm or more)
// is a clear error naming the robot, for both sampling kinds.
TEST(Candidates, ImpossibleBoxIsAnErrorNamingTheRobot) {
  Robot robot = Preset("inria-left-hand");
  robot.name = "squashed-robot";
  robot.limits.pose_box->bounds[2] = Range{0, 1};
  for (CandidateKind kind : {CandidateKind::kRandom, CandidateKind::kUniform}) {
    CandidateOptions options;
    options.kind = kind;
    options.count = 20;
    options.max_draws_per_pose = 100;
    StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
    ASSERT_FALSE(set.ok()) << CandidateKindName(kind);
    EXPECT_THAT(set.status().message(), HasSubstr("'squashed-robot'"));
    EXPECT_THAT(set.status().message(), HasSubstr("only 0 of 2000 poses"));
  }
}

// Sampling needs all six pose-box bounds; a missing one is an error naming the robot.
TEST(Candidates, IncompleteBoxIsAnError) {
  Robot robot = Preset("deltalab-table");
  robot.limits.pose_box->bounds[4].reset();
  CandidateOptions options;
  StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
  ASSERT_FALSE(set.ok());
  EXPECT_THAT(set.status().message(), HasSubstr("'deltalab-table'"));
  EXPECT_THAT(set.status().message(), HasSubstr("pose_box"));
  options.count = 0;
  EXPECT_FALSE(GenerateCandidates(Preset("deltalab-table"), options).ok());
}

// Boundary candidates: every leg reads stroke_min or stroke_max and every pose is feasible.
// The feasible mode that local FK finds from the untilted pose at all-minimum readings must be
// among them.
TEST(Candidates, BoundaryPosesAreAtStrokeEnds) {
  for (const std::string name : {"inria-left-hand", "deltalab-table"}) {
    const Robot robot = Preset(name);
    const auto begin = std::chrono::steady_clock::now();
    CandidateOptions options;
    options.kind = CandidateKind::kBoundary;
    StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
    ASSERT_TRUE(set.ok()) << set.status().message();
    EXPECT_EQ(set->draws, 64);
    EXPECT_GE(set->real_modes, static_cast<int>(set->poses.size()));
    EXPECT_FALSE(set->poses.empty()) << name;
    for (const Vector6d& v : set->poses) {
      const Pose pose = robot.PoseFromVector(v);
      const LegReadings readings = InverseKinematics(robot, pose);
      for (int i = 0; i < kNumLegs; ++i) {
        const Leg& leg = robot.legs[i];
        EXPECT_LT(std::min(std::abs(readings[i] - leg.stroke_min), std::abs(readings[i] - leg.stroke_max)), 1e-7)
            << name << " leg " << i + 1 << " at " << v.transpose();
      }
      const ConstraintReport report = EvaluateConstraints(robot, pose);
      EXPECT_TRUE(report.feasible) << name << " " << v.transpose() << ": " << report.worst_label;
    }

    LegReadings all_min;
    for (int i = 0; i < kNumLegs; ++i) all_min[i] = robot.legs[i].stroke_min;
    Pose start;
    start.position.z() = robot.legs[0].offset;
    StatusOr<LocalFkResult> lowest = ForwardKinematicsLocal(robot, all_min, start);
    ASSERT_TRUE(lowest.ok()) << lowest.status().message();
    ASSERT_TRUE(IsFeasible(robot, lowest->pose)) << name;
    const Vector6d lowest_v = robot.VectorFromPose(lowest->pose);
    EXPECT_TRUE(std::any_of(set->poses.begin(), set->poses.end(),
                            [&](const Vector6d& v) { return (v - lowest_v).cwiseAbs().maxCoeff() < 1e-6; }))
        << name << ": all-minimum pose " << lowest_v.transpose() << " missing";

    std::cout << "[ boundary ] " << name << ": " << set->poses.size() << " feasible boundary poses of "
              << set->real_modes << " real modes, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() << " s\n";
    RecordProperty(name + "_boundary_poses", static_cast<int>(set->poses.size()));
  }
}

}  // namespace
}  // namespace hexcal

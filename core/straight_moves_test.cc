#include "core/straight_moves.h"

#include <gtest/gtest.h>

#include "core/candidates.h"
#include "core/constraints.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"

namespace hexcal {
namespace {

const Vector6d kHome = (Vector6d() << 0, 0, 53.5, 0, 0, 0).finished();

Robot Inria() { return *LoadRobot("inria-left-hand"); }

// The largest distance by which any leg passes its stroke on the straight
// motion-space segment a → b, sampled four times denser than the planner
// checks it (independent of StraightSegmentHolds).
double WorstStrokeExcess(const Robot& robot, const Vector6d& a, const Vector6d& b) {
  double worst = -1e9;
  for (int k = 0; k <= 1024; ++k) {
    const LegReadings legs = InverseKinematics(robot, PoseFromMotionVector(a + (k / 1024.0) * (b - a)));
    for (int i = 0; i < kNumLegs; ++i)
      worst = std::max({worst, robot.legs[i].stroke_min - legs[i], legs[i] - robot.legs[i].stroke_max});
  }
  return worst;
}

std::vector<Vector6d> BoundaryPoses(const Robot& robot) {
  CandidateOptions options;
  options.kind = CandidateKind::kBoundary;
  return GenerateCandidates(robot, options)->poses;
}

// The README's failure (issue 33): a straight G0 from home to most boundary
// poses passes a stroke end by up to 1.4 cm. Every one of the 44 is reached
// through waypoints whose segments stay within the strokes.
TEST(StraightMovesTest, EveryBoundaryPoseIsReachedFromHomeWithinTheStrokes) {
  const Robot robot = Inria();
  const std::vector<Vector6d> targets = BoundaryPoses(robot);
  ASSERT_EQ(targets.size(), 44u);
  int direct_fails = 0;
  for (const Vector6d& target : targets) {
    const Vector6d to = MotionVectorFromPose(robot.PoseFromVector(target));
    if (WorstStrokeExcess(robot, kHome, to) > 1e-3) ++direct_fails;
    StatusOr<std::vector<Vector6d>> moves = PlanStraightMoves(robot, kHome, to);
    ASSERT_TRUE(moves.ok()) << moves.status().message();
    EXPECT_EQ(moves->back(), to);
    Vector6d at = kHome;
    const double tolerance = StraightMoveOptions().stroke_tolerance * 3.5 + 1e-9;
    for (const Vector6d& next : *moves) {
      EXPECT_LE(WorstStrokeExcess(robot, at, next), tolerance) << "to " << to.transpose();
      at = next;
    }
    EXPECT_LE(moves->size(), 12u);
  }
  EXPECT_GE(direct_fails, 9);  // the count of the default plan's poses that fail from home
}

// From one boundary pose to another (as acquire goes through a plan), too.
TEST(StraightMovesTest, BoundaryToBoundaryStaysWithinTheStrokes) {
  const Robot robot = Inria();
  const std::vector<Vector6d> targets = BoundaryPoses(robot);
  for (size_t k = 0; k + 1 < targets.size(); k += 3) {
    const Vector6d from = MotionVectorFromPose(robot.PoseFromVector(targets[k]));
    const Vector6d to = MotionVectorFromPose(robot.PoseFromVector(targets[k + 1]));
    StatusOr<std::vector<Vector6d>> moves = PlanStraightMoves(robot, from, to);
    ASSERT_TRUE(moves.ok()) << moves.status().message();
    Vector6d at = from;
    for (const Vector6d& next : *moves) {
      EXPECT_TRUE(StraightSegmentHolds(robot, at, next, from, {}));
      at = next;
    }
  }
}

// A platform left beyond a stroke end (a machine stopped at its soft limit)
// may move back in: the limit is held at the start's value, not refused.
TEST(StraightMovesTest, StartBeyondAStrokeEndMovesBack) {
  const Robot robot = Inria();
  Vector6d beyond = kHome;
  beyond[2] = 40;  // every leg below its stroke minimum
  const LegReadings legs = InverseKinematics(robot, PoseFromMotionVector(beyond));
  ASSERT_LT(legs.maxCoeff(), 0);
  StatusOr<std::vector<Vector6d>> moves = PlanStraightMoves(robot, beyond, kHome);
  ASSERT_TRUE(moves.ok()) << moves.status().message();
  EXPECT_EQ(moves->back(), kHome);
  std::string why;
  EXPECT_FALSE(StraightSegmentHolds(robot, kHome, beyond, kHome, {}, &why));
  EXPECT_NE(why.find("outside its stroke [0, 3.5]"), std::string::npos) << why;
}

// Without room to split, the error names the leg, the value and the pose.
TEST(StraightMovesTest, NoPathNamesTheLegAndItsValue) {
  const Robot robot = Inria();
  const std::vector<Vector6d> targets = BoundaryPoses(robot);
  StraightMoveOptions options;
  options.continuation_steps = 1;
  options.max_split_depth = 0;
  int refused = 0;
  for (const Vector6d& target : targets) {
    const Vector6d to = MotionVectorFromPose(robot.PoseFromVector(target));
    StatusOr<std::vector<Vector6d>> moves = PlanStraightMoves(robot, kHome, to, options);
    if (moves.ok()) continue;
    EXPECT_NE(moves.status().message().find("no straight moves from (0, 0, 53.5, 0, 0, 0) to"), std::string::npos);
    refused += moves.status().message().find(", outside its stroke [0, 3.5]") != std::string::npos;
  }
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace hexcal

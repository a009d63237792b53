// Readings an operator types (workflow/reading_check.h, CheckTypedReading):
// within the stroke they are taken; beyond it by more than the tolerance, or
// not finite, they are refused with the value and the stroke named.
#include "workflow/reading_check.h"

#include <gtest/gtest.h>

#include <limits>

#include "core/robot_io.h"

namespace hexcal::workflow {
namespace {

ReadingCheck InriaCheck() {
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");
  EXPECT_TRUE(robot.ok());
  NoiseModel noise;
  noise.leg = 0.001;
  return MakeReadingCheck(*robot, noise);
}

TEST(CheckTypedReading, WithinTheStrokeAndItsToleranceIsTaken) {
  const ReadingCheck check = InriaCheck();
  const Leg& leg = check.robot.legs[2];
  EXPECT_TRUE(CheckTypedReading(check, "a.png", 2, leg.stroke_min).ok());
  EXPECT_TRUE(CheckTypedReading(check, "a.png", 2, leg.stroke_max + 0.5 * TypedTolerance(check, 2)).ok());
  // The typed tolerance: 10 % of the INRIA robot's 3.5 cm stroke.
  EXPECT_NEAR(TypedTolerance(check, 2), 0.35, 1e-12);
  EXPECT_TRUE(CheckTypedReading(check, "a.png", 2, 0.5 * (leg.stroke_min + leg.stroke_max)).ok());
}

TEST(CheckTypedReading, BeyondTheStrokeOrNotFiniteIsRefusedByName) {
  const ReadingCheck check = InriaCheck();
  const Leg& leg = check.robot.legs[2];
  const Status far = CheckTypedReading(check, "view_0003.png", 2, 999999);
  ASSERT_FALSE(far.ok());
  EXPECT_EQ(far.kind(), StatusKind::kBadInput);
  EXPECT_NE(far.message().find("view_0003.png: L3 = 999999 cm is outside leg 3's stroke"), std::string::npos)
      << far.message();
  EXPECT_FALSE(CheckTypedReading(check, "a.png", 2, leg.stroke_min - 2 * TypedTolerance(check, 2)).ok());
  EXPECT_FALSE(CheckTypedReading(check, "a.png", 2, -1e6).ok());
  const Status huge = CheckTypedReading(check, "a.png", 0, 1e308);
  EXPECT_NE(huge.message().find("1e+308"), std::string::npos) << huge.message();
  EXPECT_FALSE(CheckTypedReading(check, "a.png", 0, std::numeric_limits<double>::infinity()).ok());
  LegReadings legs;
  for (int i = 0; i < kNumLegs; ++i) legs[i] = check.robot.legs[i].stroke_min;
  EXPECT_TRUE(CheckTypedReadings(check, "pasted line 1", legs).ok());
  legs[5] = -1e6;
  EXPECT_NE(CheckTypedReadings(check, "pasted line 1", legs).message().find("pasted line 1: L6"), std::string::npos);
}

// A capture's commanded pose: a reading far from the nominal IK length there
// is refused with the leg, the value, the length needed and the tolerance; one
// within the tolerance (an uncalibrated robot, a robot moved by hand) is taken.
TEST(CheckTypedReading, FarFromTheCommandedPosesLengthIsRefusedByName) {
  const ReadingCheck check = InriaCheck();
  const Vector6d pose = (Vector6d() << 1, -0.5, 53, 2, -1, 4).finished();
  const LegReadings needed = InverseKinematics(check.robot, check.robot.PoseFromVector(pose));
  LegReadings typed = needed;
  typed[1] += 0.9 * TypedTolerance(check, 1);
  EXPECT_TRUE(CheckTypedReadings(check, "pose_0004.png", typed, pose).ok());
  typed[3] = needed[3] + 1.5 * TypedTolerance(check, 3);
  ASSERT_GT(typed[3], check.robot.legs[3].stroke_min);  // within the stroke: only the IK says no
  ASSERT_LT(typed[3], check.robot.legs[3].stroke_max + TypedTolerance(check, 3));
  const Status far = CheckTypedReadings(check, "pose_0004.png", typed, pose);
  ASSERT_FALSE(far.ok());
  EXPECT_EQ(far.kind(), StatusKind::kBadInput);
  EXPECT_NE(far.message().find("pose_0004.png: L4 = "), std::string::npos) << far.message();
  EXPECT_NE(far.message().find("the commanded pose needs, more than 0.35 cm (10 % of the stroke)"), std::string::npos)
      << far.message();
  // Without a commanded pose (an image loaded from a folder): the stroke only.
  EXPECT_TRUE(CheckTypedReadings(check, "view_0004.png", typed).ok());
}

}  // namespace
}  // namespace hexcal::workflow

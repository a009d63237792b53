// CheckReadingsUnit against readings made by inverse kinematics on the INRIA
// robot (cm, strokes [0, 3.5]) and then scaled into other units.
#include "core/reading_units.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/inverse_kinematics.h"
#include "core/robot_io.h"

namespace hexcal {
namespace {

using ::testing::HasSubstr;

std::vector<LegReadings> InriaReadings(const Robot& robot) {
  std::vector<LegReadings> rows;
  for (double z : {52.5, 53.0, 53.5}) {
    Vector6d v;
    v << 0.5, -0.5, z, 2, -1, 3;
    rows.push_back(InverseKinematics(robot, robot.PoseFromVector(v)));
  }
  return rows;
}

TEST(CheckReadingsUnit, ReadingsInTheRobotsUnitPass) {
  const Robot robot = *LoadRobot("inria-left-hand");
  EXPECT_TRUE(CheckReadingsUnit(robot, InriaReadings(robot), "measurement").ok());
}

TEST(CheckReadingsUnit, MillimetreReadingsForACentimetreRobotAreNamed) {
  const Robot robot = *LoadRobot("inria-left-hand");
  std::vector<LegReadings> rows = InriaReadings(robot);
  for (LegReadings& row : rows) row *= 10;
  const Status s = CheckReadingsUnit(robot, rows, "measurement");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.kind(), StatusKind::kBadInput);
  EXPECT_THAT(s.message(), HasSubstr("readings look like mm, the robot 'inria-left-hand' is in cm: measurement 1: L"));
  EXPECT_THAT(s.message(), HasSubstr("far outside the stroke [0, 3.5] cm"));
}

TEST(CheckReadingsUnit, MetreReadingsForAMillimetreRobotAreNamed) {
  Robot robot = *LoadRobot("inria-left-hand");
  robot.length_unit = LengthUnit::kMetre;  // strokes [0, 3.5] m, readings in mm: 1000 times too long
  std::vector<LegReadings> rows = InriaReadings(robot);
  for (LegReadings& row : rows) row *= 1000;
  const Status s = CheckReadingsUnit(robot, rows, "");
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.message(), HasSubstr("readings look like mm, the robot 'inria-left-hand' is in m: L"));
}

// Far out but no unit explains it (one wild reading): not this check's to report.
TEST(CheckReadingsUnit, ReadingsFarOutThatNoUnitExplainsPass) {
  const Robot robot = *LoadRobot("inria-left-hand");
  std::vector<LegReadings> rows = InriaReadings(robot);
  rows[1][2] = 500;
  EXPECT_TRUE(CheckReadingsUnit(robot, rows, "measurement").ok());
  rows[1][2] = 30;  // 3 cm in mm, but the other readings are in cm
  EXPECT_TRUE(CheckReadingsUnit(robot, rows, "measurement").ok());
}

}  // namespace
}  // namespace hexcal

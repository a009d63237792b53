#include "devices/linuxcnc_geometry.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "core/constraints.h"
#include "core/inverse_kinematics.h"
#include "core/straight_moves.h"
#include "devices/hal_push.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal::workflow {
namespace {

using hexcal::testing::MatrixNear;
using hexcal::testing::Preset;
using hexcal::testing::RandomFeasiblePoses;

Eigen::Matrix3d Rx(double deg) { return Eigen::AngleAxisd(DegToRad(deg), Eigen::Vector3d::UnitX()).matrix(); }
Eigen::Matrix3d Ry(double deg) { return Eigen::AngleAxisd(DegToRad(deg), Eigen::Vector3d::UnitY()).matrix(); }
Eigen::Matrix3d Rz(double deg) { return Eigen::AngleAxisd(DegToRad(deg), Eigen::Vector3d::UnitZ()).matrix(); }

// genhexkins' inverse kinematics, written from its documentation rather than
// from hexcal's: joint_j = |P + R·platform_j − base_j|, R = Rz(C)·Ry(B)·Rx(A).
Vector6d GenhexkinsJoints(const std::map<std::string, double>& pins, const Vector6d& world) {
  const Eigen::Matrix3d rotation = Rz(world[5]) * Ry(world[4]) * Rx(world[3]);
  Vector6d joints;
  for (int j = 0; j < 6; ++j) {
    auto point = [&](const std::string& kind) {
      const std::string prefix = "genhexkins." + kind + "." + std::to_string(j) + ".";
      return Eigen::Vector3d(pins.at(prefix + "x"), pins.at(prefix + "y"), pins.at(prefix + "z"));
    };
    joints[j] = (world.head<3>() + rotation * point("platform") - point("base")).norm();
  }
  return joints;
}

// The `setp PIN VALUE` lines of a HAL file.
std::map<std::string, double> SetpPins(const std::string& hal) {
  std::map<std::string, double> pins;
  std::istringstream lines(hal);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string command, pin;
    double value = 0;
    if (words >> command >> pin >> value && command == "setp") pins[pin] = value;
  }
  return pins;
}

TEST(LinuxCncGeometry, HalPinsAreTheRobotPointsInMachineUnits) {
  const Robot robot = Preset("inria-left-hand");  // cm
  const std::map<std::string, double> pins = SetpPins(GenhexkinsHal(robot, MachineUnit::kMillimetre));
  ASSERT_EQ(pins.size(), 6u * 6u + 1u);
  EXPECT_DOUBLE_EQ(pins.at("genhexkins.base.0.x"), -97.0);  // a_1 = (-9.7, 9.1, 0) cm
  EXPECT_DOUBLE_EQ(pins.at("genhexkins.base.0.y"), 91.0);
  EXPECT_DOUBLE_EQ(pins.at("genhexkins.platform.2.x"), 78.22);  // b_3 = (7.822, -1.052, 0) cm
  EXPECT_DOUBLE_EQ(pins.at("genhexkins.platform.5.y"), -10.52);
  EXPECT_DOUBLE_EQ(pins.at("genhexkins.spindle-offset"), 0.0);
  for (int j = 0; j < 6; ++j)
    for (int k = 0; k < 3; ++k) {
      const std::string axis(1, "xyz"[k]);
      EXPECT_NEAR(pins.at("genhexkins.base." + std::to_string(j) + "." + axis), robot.legs[j].a_in_base[k] * 10, 1e-9);
      EXPECT_NEAR(pins.at("genhexkins.platform." + std::to_string(j) + "." + axis), robot.legs[j].b_in_platform[k] * 10,
                  1e-9);
    }
}

TEST(LinuxCncGeometry, InchMachineScale) {
  const Robot robot = Preset("inria-left-hand");
  EXPECT_DOUBLE_EQ(MachineUnitsPerRobotUnit(robot, MachineUnit::kMillimetre), 10.0);
  EXPECT_NEAR(MachineUnitsPerRobotUnit(robot, MachineUnit::kInch), 1 / 2.54, 1e-15);
  const std::map<std::string, double> pins = SetpPins(GenhexkinsHal(robot, MachineUnit::kInch));
  EXPECT_NEAR(pins.at("genhexkins.base.0.x"), -9.7 / 2.54, 1e-9);
}

// The whole mapping: genhexkins' joints for the world pose hexcal commands,
// with the pins hexcal writes, are hexcal's readings plus the offsets.
void ExpectGenhexkinsAgreesWithHexcal(const Robot& robot, MachineUnit unit) {
  const std::map<std::string, double> pins = SetpPins(GenhexkinsHal(robot, unit));
  for (const Vector6d& pose : RandomFeasiblePoses(robot, 20, 7)) {
    const Vector6d world = GenhexkinsWorldFromPose(robot, pose, unit);
    const Vector6d joints = GenhexkinsJoints(pins, world);
    const LegReadings expected = InverseKinematics(robot, robot.PoseFromVector(pose));
    EXPECT_TRUE(MatrixNear(ReadingsFromJoints(robot, joints, unit), expected, 1e-8));
    EXPECT_TRUE(MatrixNear(JointsFromReadings(robot, expected, unit), joints, 1e-7));
  }
}

TEST(LinuxCncGeometry, GenhexkinsJointsAreHexcalReadingsPlusOffsets) {
  ExpectGenhexkinsAgreesWithHexcal(Preset("inria-left-hand"), MachineUnit::kMillimetre);
  ExpectGenhexkinsAgreesWithHexcal(Preset("inria-left-hand"), MachineUnit::kInch);
  ExpectGenhexkinsAgreesWithHexcal(Preset("deltalab-table"), MachineUnit::kMillimetre);
}

TEST(LinuxCncGeometry, ZyxRobotAnglesAreConvertedThroughTheRotation) {
  Robot robot = Preset("inria-left-hand");
  robot.euler = EulerConvention::kZYX;  // R = Rx(q3)·Ry(q2)·Rz(q1)
  Vector6d pose;
  pose << 1, -2, 53, 10, -5, 7;
  const Vector6d world = GenhexkinsWorldFromPose(robot, pose, MachineUnit::kMillimetre);
  EXPECT_TRUE(MatrixNear(Rz(world[5]) * Ry(world[4]) * Rx(world[3]), Rx(7) * Ry(-5) * Rz(10), 1e-12));
  EXPECT_TRUE(MatrixNear(world.head<3>(), Eigen::Vector3d(10, -20, 530), 1e-12));
  ExpectGenhexkinsAgreesWithHexcal(robot, MachineUnit::kMillimetre);
}

TEST(LinuxCncGeometry, XyzRobotAnglesPassUnchanged) {
  const Robot robot = Preset("inria-left-hand");
  Vector6d pose;
  pose << 1, -2, 53, 10, -5, 7;
  Vector6d expected;
  expected << 10, -20, 530, 10, -5, 7;
  EXPECT_TRUE(MatrixNear(GenhexkinsWorldFromPose(robot, pose, MachineUnit::kMillimetre), expected, 1e-12));
}

TEST(LinuxCncGeometry, UnitsAndNumbers) {
  EXPECT_TRUE(ParseMachineUnit("MM") == MachineUnit::kMillimetre);
  EXPECT_TRUE(ParseMachineUnit("inch") == MachineUnit::kInch);
  EXPECT_FALSE(ParseMachineUnit("custom").has_value());
  EXPECT_EQ(FixedNumber(535.0), "535");
  EXPECT_EQ(FixedNumber(-0.25), "-0.25");
  EXPECT_EQ(FixedNumber(-1e-12), "0");
  EXPECT_EQ(FixedNumber(1.0 / 3.0, 6), "0.333333");
}

// A sideways move: a leg's length along a straight line is convex, shortest
// where the leg is most upright, here between the end points. The strokes
// are set to just hold both end poses; the middle is outside them (checked
// here, so the case cannot pass vacuously).
TEST(LinuxCncGeometry, AStraightMoveWhoseMiddleLeavesAStrokeIsRefused) {
  Robot robot = Preset("inria-left-hand");
  Vector6d from, to, middle;
  from << -6, -6, 53.5, 0, 0, 0;
  to << 6, 6, 53.5, 0, 0, 0;
  middle << 0, 0, 53.5, 0, 0, 0;
  const LegReadings a = InverseKinematics(robot, robot.PoseFromVector(from));
  const LegReadings b = InverseKinematics(robot, robot.PoseFromVector(to));
  const LegReadings m = InverseKinematics(robot, robot.PoseFromVector(middle));
  bool middle_outside = false;
  for (int i = 0; i < kNumLegs; ++i) {
    robot.legs[i].stroke_min = std::min(a[i], b[i]) - 1e-3;
    robot.legs[i].stroke_max = std::max(a[i], b[i]) + 1e-3;
    middle_outside |= !WithinStroke(robot.legs[i], m[i]);
  }
  ASSERT_TRUE(middle_outside);
  const auto world = [&](const Vector6d& pose) {
    return GenhexkinsWorldFromPose(robot, pose, MachineUnit::kMillimetre);
  };
  // genhexkins' world is core/straight_moves.h's motion space in machine units.
  const auto motion = [&](const Vector6d& pose) { return MotionVectorFromPose(robot.PoseFromVector(pose)); };
  EXPECT_TRUE(MatrixNear(world(to).head<3>() / 10, motion(to).head<3>(), 1e-12));
  EXPECT_TRUE(MatrixNear(world(to).tail<3>(), motion(to).tail<3>(), 1e-12));
  EXPECT_FALSE(StraightSegmentHolds(robot, motion(from), motion(to), motion(from), {}));
  EXPECT_TRUE(StraightSegmentHolds(robot, motion(from), motion(from), motion(from), {}));
  // Round trip of the world form.
  const Pose back = PoseFromGenhexkinsWorld(robot, world(to), MachineUnit::kMillimetre);
  EXPECT_TRUE(MatrixNear(robot.VectorFromPose(back), to, 1e-9));
}

TEST(LinuxCncGeometry, HomeShiftsAreTheOffsetChangesInMachineUnits) {
  const Robot running = Preset("inria-left-hand");  // cm
  Robot calibrated = running;
  calibrated.legs[2].offset += 0.041;  // cm
  StatusOr<std::array<double, 6>> shifts = HomeShifts(running, calibrated, MachineUnit::kMillimetre);
  ASSERT_TRUE(shifts.ok()) << shifts.status().message();
  EXPECT_NEAR((*shifts)[2], 0.41, 1e-12);
  EXPECT_EQ((*shifts)[0], 0);
  // The same robots, one in mm: each converted from its own unit (issue 33:
  // "add -4702.464 mm" came from reading the mm robot's l as cm).
  Robot running_mm = running;
  running_mm.length_unit = LengthUnit::kMillimetre;
  for (Leg& leg : running_mm.legs) {
    leg.a_in_base *= 10, leg.b_in_platform *= 10, leg.offset *= 10;
    leg.stroke_min *= 10, leg.stroke_max *= 10;
  }
  shifts = HomeShifts(running_mm, calibrated, MachineUnit::kInch);
  ASSERT_TRUE(shifts.ok()) << shifts.status().message();
  EXPECT_NEAR((*shifts)[2], 0.41 / 25.4, 1e-12);
  // A calibrated file whose unit is wrong is not the same machine.
  Robot wrong_unit = calibrated;
  wrong_unit.length_unit = LengthUnit::kMillimetre;
  shifts = HomeShifts(running, wrong_unit, MachineUnit::kMillimetre);
  ASSERT_FALSE(shifts.ok());
  EXPECT_NE(shifts.status().message().find("not the same machine, or a robot file in another length unit"),
            std::string::npos);
}

TEST(LinuxCncGeometry, ExactFixedNumbersReadBackAsTheSameDouble) {
  for (double value : {0.0, 1.0, -0.25, 522.496, 0.1 + 0.2, 1.0 / 3.0, 1234567.891011, -1e-9, 3e-12, 98765.4321e3}) {
    const std::string text = ExactFixedNumber(value);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), value) << text;
    EXPECT_EQ(text.find_first_of("eE"), std::string::npos) << text;
  }
  EXPECT_EQ(ExactFixedNumber(522.496), "522.496");
  EXPECT_EQ(ExactFixedNumber(-0.0), "0");
}

TEST(LinuxCncGeometry, RobotsOutsideMachineSizesAreRefused) {
  Robot robot = Preset("inria-left-hand");
  EXPECT_TRUE(CheckRobotForMachine(robot).ok());
  for (double scale : {1e70, 1e-12}) {
    Robot scaled = robot;
    for (Leg& leg : scaled.legs) leg.a_in_base *= scale, leg.b_in_platform *= scale;
    const Status checked = CheckRobotForMachine(scaled);
    EXPECT_FALSE(checked.ok()) << scale;
    EXPECT_NE(checked.message().find("is its length_unit right?"), std::string::npos) << checked.message();
  }
  robot.legs[4].offset = std::nan("");
  EXPECT_NE(CheckRobotForMachine(robot).message().find("not finite"), std::string::npos);
}

TEST(LinuxCncGeometry, NamesCannotBecomeHalCommands) {
  Robot robot = Preset("inria-left-hand");
  robot.name = "evil\nloadusr /bin/sh -c reboot\r\x1b";
  const std::string hal = GenhexkinsHal(robot, MachineUnit::kMillimetre);
  std::istringstream lines(hal);
  for (std::string line; std::getline(lines, line);)
    EXPECT_TRUE(line.empty() || line[0] == '#' || line.rfind("setp ", 0) == 0) << line;
  EXPECT_NE(hal.find("evil\\x0aloadusr /bin/sh -c reboot\\x0d\\x1b"), std::string::npos) << hal;
}

}  // namespace
}  // namespace hexcal::workflow

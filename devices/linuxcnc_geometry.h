// hexcal's robot model in LinuxCNC's terms: the genhexkins kinematics module
// (docs/acquisition.md, "A real LinuxCNC machine").
//
// genhexkins computes joint j (0..5) as the full length of leg j+1,
//   joint_j = |P + R·platform_j − base_j|,   R = Rz(C)·Ry(B)·Rx(A), degrees,
// with the world pose X Y Z A B C = the platform origin P in the base frame
// and its roll, pitch, yaw. hexcal's model is |P + R·b_i − a_i| = L_i + l_i
// (core/robot.h), so:
//   genhexkins.base.j      = a_(j+1)      (base frame)
//   genhexkins.platform.j  = b_(j+1)      (platform frame)
//   joint_j                = L_(j+1) + l_(j+1)
// The offsets l_i are not kinematics pins: they are where each joint's
// position scale starts (the [JOINT_j] HOME / HOME_OFFSET of the INI: the
// full leg length at the home switch). Angles: hexcal's `xyz` convention is
// genhexkins' (A = q1, B = q2, C = q3); a `zyx` robot's angles are converted
// through the rotation matrix. genhexkins.spindle-offset and tool-offset
// shift the base and platform points along z and must be 0 for this model.
//
// Lengths: LinuxCNC works in the INI's [TRAJ] LINEAR_UNITS (mm or inch), the
// robot file in its length_unit (mm, cm or m); these functions convert.
//
//   Vector6d world = GenhexkinsWorldFromPose(robot, pose, MachineUnit::kMillimetre);
//   LegReadings legs = ReadingsFromJoints(robot, joint_pos, MachineUnit::kMillimetre);
//   std::string hal = GenhexkinsHal(robot, MachineUnit::kMillimetre);
#pragma once

#include <optional>
#include <string>

#include "core/inverse_kinematics.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal::workflow {

// LinuxCNC's linear units: the INI accepts mm and inch (G21, G20).
enum class MachineUnit { kMillimetre, kInch };
// "mm" or "inch", any case; LinuxCNC's own spellings "metric", "in" too.
std::optional<MachineUnit> ParseMachineUnit(const std::string& text);
const char* MachineUnitName(MachineUnit unit);  // "mm", "inch"
// Machine units per robot unit: 10 for a cm robot on a mm machine.
double MachineUnitsPerRobotUnit(const Robot& robot, MachineUnit unit);

// The world pose genhexkins moves to for hexcal's pose [x, y, z, q1, q2, q3]
// (robot unit, degrees, the robot's Euler convention): X Y Z in machine
// units, A B C in degrees.
Vector6d GenhexkinsWorldFromPose(const Robot& robot, const Vector6d& pose, MachineUnit unit);
// The inverse: the platform pose of a genhexkins world pose.
Pose PoseFromGenhexkinsWorld(const Robot& robot, const Vector6d& world, MachineUnit unit);
// hexcal's readings L (robot unit) from genhexkins joints (full leg lengths,
// machine units): L_i = joint_(i-1) / scale − l_i.
LegReadings ReadingsFromJoints(const Robot& robot, const Vector6d& joints, MachineUnit unit);
// The inverse: the joints (machine units) at which the sensors read `readings`.
Vector6d JointsFromReadings(const Robot& robot, const LegReadings& readings, MachineUnit unit);

// `value` with `decimals` decimals, trailing zeros dropped ("535", "-0.25"):
// G-code and HAL take no exponents.
std::string FixedNumber(double value, int decimals = 9);
// `value` in fixed notation with the fewest decimals (at most 17) that read
// back as the same double: full precision without an exponent.
std::string ExactFixedNumber(double value);

// The sizes a robot may have to be written for a machine: its anchor points
// within kMaxMachineRobotMetres of the origin, the farthest at least
// kMinMachineRobotMetres (a robot file in the wrong unit is 1000 times off).
constexpr double kMinMachineRobotMetres = 1e-3;
constexpr double kMaxMachineRobotMetres = 100;
// Bad input naming the robot and the size when it is outside those bounds or
// a value is not finite.
Status CheckRobotForMachine(const Robot& robot);

// A name for a HAL or INI comment: every byte that is not printable ASCII
// (a line break would end the comment and start a command) as \xNN.
std::string CommentText(const std::string& name);

// A HAL file for the robot's geometry: `setp genhexkins.base.N.{x,y,z}` and
// `setp genhexkins.platform.N.{x,y,z}` for N = 0..5 in machine units,
// spindle-offset 0, and comments giving each joint's offset l (machine units)
// for the INI's joint home positions. Values at full precision
// (ExactFixedNumber); the robot is one CheckRobotForMachine accepts.
std::string GenhexkinsHal(const Robot& robot, MachineUnit unit);

}  // namespace hexcal::workflow

#include "devices/linuxcnc_geometry.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <sstream>

#include "core/constraints.h"

namespace hexcal::workflow {
namespace {

double MetresPerMachineUnit(MachineUnit unit) { return unit == MachineUnit::kInch ? 0.0254 : 0.001; }

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

void AppendPoint(std::ostringstream& hal, const std::string& pin_prefix, const Eigen::Vector3d& point, double scale) {
  static const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    hal << "setp " << pin_prefix << "." << axes[k] << " " << ExactFixedNumber(point[k] * scale) << "\n";
}

std::string PrintfFixed(double value, int decimals) {
  const int size = std::snprintf(nullptr, 0, "%.*f", decimals, value);
  std::string text(static_cast<size_t>(size) + 1, '\0');
  std::snprintf(text.data(), text.size(), "%.*f", decimals, value);
  text.pop_back();
  return text;
}

// The farthest anchor point from its frame's origin, metres; NaN if one is not finite.
double RobotSizeMetres(const Robot& robot) {
  double size = 0;
  for (const Leg& leg : robot.legs) {
    const bool finite = leg.a_in_base.allFinite() && leg.b_in_platform.allFinite() && std::isfinite(leg.offset) &&
                        std::isfinite(leg.stroke_min) && std::isfinite(leg.stroke_max);
    if (!finite) return std::nan("");
    size = std::max({size, leg.a_in_base.norm(), leg.b_in_platform.norm()});
  }
  return size * MetresPerUnit(robot.length_unit);
}

}  // namespace

std::optional<MachineUnit> ParseMachineUnit(const std::string& text) {
  const std::string unit = Lower(text);
  if (unit == "mm" || unit == "metric") return MachineUnit::kMillimetre;
  if (unit == "inch" || unit == "in" || unit == "imperial") return MachineUnit::kInch;
  return std::nullopt;
}

const char* MachineUnitName(MachineUnit unit) { return unit == MachineUnit::kInch ? "inch" : "mm"; }

double MachineUnitsPerRobotUnit(const Robot& robot, MachineUnit unit) {
  return MetresPerUnit(robot.length_unit) / MetresPerMachineUnit(unit);
}

Vector6d GenhexkinsWorldFromPose(const Robot& robot, const Vector6d& pose, MachineUnit unit) {
  const Pose platform = robot.PoseFromVector(pose);
  // genhexkins' roll-pitch-yaw is hexcal's xyz convention (core/pose.h).
  const Vector6d xyz_form = VectorFromPose(platform, EulerConvention::kXYZ);
  Vector6d world = xyz_form;
  world.head<3>() *= MachineUnitsPerRobotUnit(robot, unit);
  return world;
}

Pose PoseFromGenhexkinsWorld(const Robot& robot, const Vector6d& world, MachineUnit unit) {
  Vector6d xyz_form = world;
  xyz_form.head<3>() /= MachineUnitsPerRobotUnit(robot, unit);
  return PoseFromVector(xyz_form, EulerConvention::kXYZ);
}

LegReadings ReadingsFromJoints(const Robot& robot, const Vector6d& joints, MachineUnit unit) {
  const double scale = MachineUnitsPerRobotUnit(robot, unit);
  LegReadings readings;
  for (int i = 0; i < kNumLegs; ++i) readings[i] = joints[i] / scale - robot.legs[i].offset;
  return readings;
}

Vector6d JointsFromReadings(const Robot& robot, const LegReadings& readings, MachineUnit unit) {
  const double scale = MachineUnitsPerRobotUnit(robot, unit);
  Vector6d joints;
  for (int i = 0; i < kNumLegs; ++i) joints[i] = (readings[i] + robot.legs[i].offset) * scale;
  return joints;
}

std::string FixedNumber(double value, int decimals) {
  std::string fixed = PrintfFixed(value, decimals);
  if (fixed.find('.') != std::string::npos) {
    fixed.erase(fixed.find_last_not_of('0') + 1);
    if (fixed.back() == '.') fixed.pop_back();
  }
  return fixed == "-0" ? "0" : fixed;
}

std::string ExactFixedNumber(double value) {
  for (int decimals = 0; decimals < 17; ++decimals) {
    const std::string text = FixedNumber(value, decimals);
    if (std::strtod(text.c_str(), nullptr) == value) return text;
  }
  return FixedNumber(value, 17);
}

Status CheckRobotForMachine(const Robot& robot) {
  const double size = RobotSizeMetres(robot);
  if (std::isnan(size)) return Status::BadInput("robot '" + CommentText(robot.name) + "': a value is not finite");
  if (size < kMinMachineRobotMetres || size > kMaxMachineRobotMetres) {
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.3g", size);
    return Status::BadInput("robot '" + CommentText(robot.name) + "': its farthest anchor point is " + shown +
                            " m from its frame's origin, outside [" + FixedNumber(kMinMachineRobotMetres) + ", " +
                            FixedNumber(kMaxMachineRobotMetres) + "] m: is its length_unit right?");
  }
  return Status::Ok();
}

std::string CommentText(const std::string& name) {
  std::string text;
  for (unsigned char c : name) {
    if (c >= 0x20 && c < 0x7f) {
      text += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      text += escaped;
    }
  }
  return text;
}

std::string GenhexkinsHal(const Robot& robot, MachineUnit unit) {
  const double scale = MachineUnitsPerRobotUnit(robot, unit);
  const char* name = MachineUnitName(unit);
  std::ostringstream hal;
  hal << "# genhexkins geometry of robot '" << CommentText(robot.name) << "', written by hexcal export (docs/acquisition.md).\n"
      << "# Lengths in " << name << " (the INI's [TRAJ] LINEAR_UNITS = " << name << "); the robot file is in "
      << LengthUnitName(robot.length_unit) << ".\n"
      << "# base.N = a_(N+1) in the base frame, platform.N = b_(N+1) in the platform frame;\n"
      << "# joint N = the full length of leg N+1 = hexcal's reading L_(N+1) + offset l_(N+1).\n";
  for (int j = 0; j < kNumLegs; ++j) {
    const Leg& leg = robot.legs[j];
    hal << "\n# leg " << j + 1 << ": l = " << FixedNumber(leg.offset * scale) << " " << name << "; stroke L in ["
        << FixedNumber(leg.stroke_min * scale) << ", " << FixedNumber(leg.stroke_max * scale) << "] = joint " << j
        << " in [" << FixedNumber((leg.stroke_min + leg.offset) * scale) << ", "
        << FixedNumber((leg.stroke_max + leg.offset) * scale) << "]\n";
    AppendPoint(hal, "genhexkins.base." + std::to_string(j), leg.a_in_base, scale);
    AppendPoint(hal, "genhexkins.platform." + std::to_string(j), leg.b_in_platform, scale);
  }
  hal << "\n# Both offsets move the base and platform points along z: hexcal's model has neither.\n"
      << "# (genhexkins.tool-offset must stay 0 too: do not net it to motion.tooloffset.z.)\n"
      << "setp genhexkins.spindle-offset 0\n";
  return hal.str();
}

}  // namespace hexcal::workflow

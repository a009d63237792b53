// The robot model: a 6-6 Gough-Stewart platform with the paper's 7 parameters
// per leg (section 5.1, eq. 3):  |P + R b_i - a_i| = L_i + l_i
//   a_i  base attachment point, in the base frame
//   b_i  platform attachment point, in the platform frame
//   l_i  length offset: the part of the leg length the sensor does not read
//   L_i  sensor reading, within [stroke_min, stroke_max]
// All lengths are in the robot's length_unit. Files: docs/robot-file.md.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "core/pose.h"

namespace hexcal {

constexpr int kNumLegs = 6;
constexpr int kParamsPerLeg = 7;                      // a (3), b (3), l
constexpr int kNumParams = kNumLegs * kParamsPerLeg;  // 42

enum class LengthUnit { kMillimetre, kCentimetre, kMetre };
std::optional<LengthUnit> ParseLengthUnit(const std::string& text);
const char* LengthUnitName(LengthUnit unit);
double MetresPerUnit(LengthUnit unit);

struct Leg {
  Eigen::Vector3d a_in_base = Eigen::Vector3d::Zero();
  Eigen::Vector3d b_in_platform = Eigen::Vector3d::Zero();
  double offset = 0;      // l_i
  double stroke_min = 0;  // reading range of L_i
  double stroke_max = 0;
};

struct Range {
  double min = 0;
  double max = 0;
  bool Contains(double v) const { return v >= min && v <= max; }
  double Centre() const { return 0.5 * (min + max); }
};

// Bounds on [x, y, z, q1, q2, q3] (lengths in the robot unit, angles in degrees).
// A coordinate without bounds is unconstrained.
struct PoseBox {
  std::array<std::optional<Range>, 6> bounds;
  bool IsComplete() const {
    for (const auto& b : bounds)
      if (!b) return false;
    return true;
  }
};

// The working assembly mode (the paper's section 5.3 bounds its search by "the
// sign of the inverse kinematic Jacobian matrix"): a robot moving from `pose`
// cannot cross a parallel singularity, so a pose is in its workspace only where
// det J_IK has the sign it has at `pose`, and, with min_det_ratio > 0, at least
// that fraction of its size there (clear of the singularity's neighbourhood).
struct AssemblyMode {
  Vector6d pose = Vector6d::Zero();  // [x, y, z, q1, q2, q3] of a pose in the mode
  double min_det_ratio = 0;          // in [0, 1)
};

// Workspace limits; every one is optional.
struct RobotLimits {
  // Angle between a leg and the base normal (+z of the base frame), degrees.
  std::optional<double> base_joint_max_deg;
  // Angle between a leg and the platform normal (+z of the platform frame), degrees.
  std::optional<double> platform_joint_max_deg;
  // Smallest allowed distance between two leg segments, robot unit.
  std::optional<double> leg_min_distance;
  std::optional<AssemblyMode> assembly_mode;
  std::optional<PoseBox> pose_box;
  // Where random and uniform poses are drawn (an operator's calibration
  // workspace, like the paper's random poses), intersected with pose_box.
  // Defaults to pose_box. Not a constraint: planned poses may leave it.
  std::optional<PoseBox> sampling_box;

  // The box random/uniform sampling uses: sampling_box ∩ pose_box, or pose_box.
  std::optional<PoseBox> SamplingBox() const;
};

struct Robot {
  std::string name;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  EulerConvention euler = EulerConvention::kXYZ;
  std::array<Leg, kNumLegs> legs;
  RobotLimits limits;

  Pose PoseFromVector(const Vector6d& v) const { return hexcal::PoseFromVector(v, euler); }
  Vector6d VectorFromPose(const Pose& p) const { return hexcal::VectorFromPose(p, euler); }
};

// The 42 parameters in the order [a_1, b_1, l_1, a_2, b_2, l_2, ...].
using ParameterVector = Eigen::Matrix<double, kNumParams, 1>;
using LegParameters = Eigen::Matrix<double, kParamsPerLeg, 1>;
ParameterVector ParametersOf(const Robot& robot);
LegParameters LegParametersOf(const Leg& leg);
// A copy of `robot` with its 42 parameters replaced (strokes and limits kept).
Robot WithParameters(const Robot& robot, const ParameterVector& params);

// The centre of the robot's sampling box (robot unit, degrees; zero without
// one): where the sim machine starts, and the LinuxCNC controller's via pose.
Vector6d WorkspaceCentre(const Robot& robot);

}  // namespace hexcal

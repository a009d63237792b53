// Workspace constraints of a pose, each as a signed margin: positive inside,
// zero on the boundary, negative outside. Margins are in the natural unit of
// the constraint (robot length unit for strokes and leg distances, degrees for
// joint angles and the angular pose-box bounds; the assembly mode's is the
// ratio det J_IK(pose) / det J_IK(mode pose) less its min_det_ratio).
//
//   ConstraintReport report = EvaluateConstraints(robot, pose);
//   if (!report.feasible) std::cout << report.worst_label << " " << report.worst_margin;
#pragma once

#include <string>
#include <vector>

#include "core/pose.h"
#include "core/robot.h"

namespace hexcal {

enum class ConstraintKind {
  kStrokeMin,
  kStrokeMax,
  kBaseJoint,
  kPlatformJoint,
  kLegDistance,
  kAssemblyMode,
  kPoseBox
};

struct ConstraintMargin {
  ConstraintKind kind;
  std::string label;  // e.g. "stroke max L3", "base joint 2", "leg distance 1-4", "assembly mode", "pose box q2 max"
  double margin;
};

// A pose on a limit (a boundary pose has readings exactly at the stroke ends)
// comes back from IK a few ulps outside; margins above -kFeasibilityTolerance
// count as satisfied.
constexpr double kFeasibilityTolerance = 1e-9;

// A reading inside [stroke_min, stroke_max] within kFeasibilityTolerance: the
// one stroke test of the planner, the status and the GUI's 3D view.
bool WithinStroke(const Leg& leg, double reading);

struct ConstraintReport {
  std::vector<ConstraintMargin> margins;
  bool feasible = true;
  double worst_margin = 0;  // the smallest margin
  std::string worst_label;
};

ConstraintReport EvaluateConstraints(const Robot& robot, const Pose& pose);
// Same verdict as EvaluateConstraints(...).feasible, without building labels.
bool IsFeasible(const Robot& robot, const Pose& pose);

// Every margin in the order EvaluateConstraints reports them, without labels
// (for optimisers). Pose-box margins are left out when include_box is false.
std::vector<double> ConstraintMargins(const Robot& robot, const Pose& pose, bool include_box = true);

// Shortest distance between segments [p0, p1] and [q0, q1].
double SegmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                       const Eigen::Vector3d& q1);

}  // namespace hexcal

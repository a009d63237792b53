#include "devices/controller.h"

#include <cmath>

#include "core/constraints.h"
#include "core/csv.h"

namespace hexcal::workflow {
Status CheckPoseInWorkspace(const Robot& robot, const Vector6d& pose) {
  const ConstraintReport report = EvaluateConstraints(robot, robot.PoseFromVector(pose));
  if (report.feasible) return Status::Ok();
  return Status::BadInput("pose " + PoseText(pose) + " is out of the robot's workspace: " + report.worst_label +
                          " by " + FormatNumber(std::round(-report.worst_margin * 1e4) / 1e4));
}

std::string PoseText(const Vector6d& pose) {
  std::string text = "(";
  for (int k = 0; k < 6; ++k) text += FormatNumber(pose[k]) + (k < 5 ? ", " : ")");
  return text;
}

}  // namespace hexcal::workflow

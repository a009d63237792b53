// JSON forms of core types, shared by every result a workflow step returns
// (and so by `hexcal ... --json` and the files in results/).
//
//   json["robot"] = RobotJson(robot);  // read back: RobotFromJson(JsonFields(json["robot"], "report.json"))
//   json["pose"] = PoseJson(robot, pose);  // robot unit, degrees in the robot's Euler convention
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/observability.h"
#include "core/robot.h"
#include "core/status.h"
#include "session/json_fields.h"

namespace hexcal::workflow {

// {"x", "y", "z", "q1", "q2", "q3"} in the robot's unit and Euler convention.
nlohmann::json PoseJson(const Robot& robot, const Pose& pose);
// {"O1".."O4", "sigma_min", "sigma_max", "poses"}.
nlohmann::json IndicesJson(const ObservabilityIndices& indices);
// {"name", "length_unit", "euler", "legs": [{"a", "b", "l", "stroke"}]}; the
// pose limits are not part of this form (they stay in the robot file).
nlohmann::json RobotJson(const Robot& robot);
Robot RobotFromJson(JsonFields fields);

}  // namespace hexcal::workflow

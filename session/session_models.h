// The session's models as session.yaml names them: the file a name stands
// for (relative to the session folder, or a preset or a path), and the
// robot, camera and target loaded. Below every session step and the sim
// world, which all read them (split from session_calibrate.h, issue 37: the
// sim world and the measure step included the calibrate step for these).
//
//   StatusOr<SessionModels> models = LoadSessionModels("run1");
//   if (!models.ok()) return models.status();
//   const Robot& nominal = models->robot;
//   StatusOr<Robot> robot = LoadSessionRobot("run1", config);  // the robot alone
#pragma once

#include <string>

#include "core/robot.h"
#include "core/session.h"
#include "core/status.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::workflow {

// A name in session.yaml: a file relative to the session folder when one
// exists there, otherwise as given (a preset name or a path).
std::string ResolveSessionFile(const std::string& dir, const std::string& name);

// The robot session.yaml names (`config`, loaded from DIR), loaded: what a
// step that needs only the robot reads.
StatusOr<Robot> LoadSessionRobot(const std::string& dir, const SessionConfig& config);

// The session's configuration and the robot, camera and target it names, loaded.
struct SessionModels {
  SessionConfig config;
  Robot robot;
  Camera camera;
  Target target;
};
StatusOr<SessionModels> LoadSessionModels(const std::string& dir);

}  // namespace hexcal::workflow

#include "workflow/session_init.h"

#include <filesystem>

#include "core/robot_io.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::workflow {

std::string AsSessionPath(const std::string& dir, const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(fs::symlink_status(name, error))) return name;
  const fs::path file = fs::absolute(name, error).lexically_normal();
  const fs::path relative = file.lexically_relative(fs::absolute(dir, error).lexically_normal());
  return error || relative.empty() ? file.string() : relative.string();
}

Status CreateSession(const std::string& dir, SessionConfig config) {
  // The names are checked as given (from the current directory), before
  // anything is written.
  if (StatusOr<Robot> robot = LoadRobot(config.robot); !robot.ok()) return robot.status();
  config.robot = AsSessionPath(dir, config.robot);
  if (config.instrument == Instrument::kCamera) {
    if (StatusOr<Camera> camera = LoadCamera(config.camera); !camera.ok()) return camera.status();
    if (StatusOr<Target> target = LoadTarget(config.target); !target.ok()) return target.status();
    for (std::string* name : {&config.camera, &config.target}) *name = AsSessionPath(dir, *name);
  }
  return InitSession(dir, config);
}

}  // namespace hexcal::workflow

#include "session/session_models.h"

#include <filesystem>

#include "core/robot_io.h"

namespace hexcal::workflow {

namespace fs = std::filesystem;

std::string ResolveSessionFile(const std::string& dir, const std::string& name) {
  std::error_code error;
  const fs::path in_session = fs::path(dir) / name;
  return fs::exists(in_session, error) ? in_session.string() : name;
}

StatusOr<Robot> LoadSessionRobot(const std::string& dir, const SessionConfig& config) {
  return LoadRobot(ResolveSessionFile(dir, config.robot));
}

StatusOr<SessionModels> LoadSessionModels(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
  if (!robot.ok()) return robot.status();
  StatusOr<Camera> camera = LoadCamera(ResolveSessionFile(dir, config->camera));
  if (!camera.ok()) return camera.status();
  StatusOr<Target> target = LoadTarget(ResolveSessionFile(dir, config->target));
  if (!target.ok()) return target.status();
  return SessionModels{std::move(*config), std::move(*robot), std::move(*camera), std::move(*target)};
}

}  // namespace hexcal::workflow

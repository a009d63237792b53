#include "workflow/session_plan_model.h"

#include "core/point_file.h"
#include "session/session_models.h"

namespace hexcal::workflow {

StatusOr<PlanningModel> SessionPlanningModel(const std::string& dir, const SessionConfig& config, const Robot& robot) {
  PlanningModel model{robot, config.noise, std::nullopt};
  if (config.instrument != Instrument::kPoints) return model;
  const std::string where = SessionPaths(dir).config + ": ";
  if (config.reflectors.empty()) {
    if (!config.tracker) return model;  // the fits' pose noise, one for every pose
    return Status::BadInput(where + "tracker: planning for the tracker needs the reflectors' positions (reflectors: "
                                 "a CSV point,x,y,z)");
  }
  StatusOr<std::vector<NamedPoint>> reflectors =
      LoadReflectorFile(ResolveSessionFile(dir, config.reflectors), config.reflectors);
  if (!reflectors.ok()) return reflectors.status();
  std::vector<Eigen::Vector3d> positions;
  for (const NamedPoint& r : *reflectors) positions.push_back(r.position);
  StatusOr<TrackerModel> tracker =
      MakeTrackerModel(robot, positions, config.point_sigma, config.tracker.value_or(TrackerSettings{}),
                       config.platform_from_target.value_or(Pose{}));
  if (!tracker.ok()) return Status::BadInput(where + tracker.status().message());
  model.tracker = *tracker;
  return model;
}

StatusOr<PlanningModel> SessionPlanningModel(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
  if (!robot.ok()) return robot.status();
  return SessionPlanningModel(dir, *config, *robot);
}

}  // namespace hexcal::workflow

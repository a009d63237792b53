#include "app/commands/cli_common.h"

#include <unistd.h>

#include <iostream>
#include <sstream>

#include "core/csv.h"

namespace hexcal::cli {

int ReportError(std::ostream& err, const std::string& command, const Status& status, int code) {
  err << "hexcal " << command << ": " << status.message() << "\n";
  return code;
}

nlohmann::json PoseJson(const Robot& robot, const Pose& pose) {
  const Vector6d v = robot.VectorFromPose(pose);
  return {{"x", v[0]}, {"y", v[1]}, {"z", v[2]}, {"q1", v[3]}, {"q2", v[4]}, {"q3", v[5]}};
}

nlohmann::json IndicesJson(const ObservabilityIndices& o) {
  return {{"O1", o.o1},
          {"O2", o.o2},
          {"O3", o.o3},
          {"O4", o.o4},
          {"sigma_min", o.sigma_min},
          {"sigma_max", o.sigma_max},
          {"poses", o.num_poses}};
}

nlohmann::json RobotJson(const Robot& robot) {
  nlohmann::json legs = nlohmann::json::array();
  for (const Leg& leg : robot.legs) {
    legs.push_back({{"a", {leg.a_in_base.x(), leg.a_in_base.y(), leg.a_in_base.z()}},
                    {"b", {leg.b_in_platform.x(), leg.b_in_platform.y(), leg.b_in_platform.z()}},
                    {"l", leg.offset},
                    {"stroke", {leg.stroke_min, leg.stroke_max}}});
  }
  return {{"name", robot.name},
          {"length_unit", LengthUnitName(robot.length_unit)},
          {"euler", EulerConventionName(robot.euler)},
          {"legs", legs}};
}

StatusOr<std::vector<double>> ParseNumberList(const std::string& text, int count, const std::string& what) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    StatusOr<double> value = ParseNumber(item);
    if (!value.ok()) return Status::Error(what + ": '" + item + "' is not a finite number");
    values.push_back(*value);
  }
  if (static_cast<int>(values.size()) != count) {
    return Status::Error(what + ": expected " + std::to_string(count) + " comma-separated numbers, got " +
                         std::to_string(values.size()));
  }
  return values;
}

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && last_percent_ >= 0) std::cerr << "\n";
}

void ProgressBar::Update(int done, int total) {
  if (!enabled_ || total <= 0) return;
  const int percent = static_cast<int>(100.0 * done / total);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  const int width = 30, filled = width * percent / 100;
  std::cerr << "\r" << label_ << " [" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << percent
            << "% (" << done << "/" << total << ")" << std::flush;
}

}  // namespace hexcal::cli

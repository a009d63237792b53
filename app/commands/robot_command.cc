// hexcal robot check|show ROBOT [--json]
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"

namespace hexcal::cli {
namespace {

struct RobotOptions {
  std::string robot;
  bool json = false;
};

void PrintRobot(const Robot& robot, std::ostream& out) {
  const char* unit = LengthUnitName(robot.length_unit);
  out << "robot " << robot.name << " (lengths in " << unit << ", euler " << EulerConventionName(robot.euler) << ")\n";
  out << "leg        a (base)                     b (platform)               l          stroke\n";
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    out << std::setw(3) << i + 1 << std::fixed << std::setprecision(4);
    for (int k = 0; k < 3; ++k) out << std::setw(9) << leg.a_in_base[k];
    out << "  ";
    for (int k = 0; k < 3; ++k) out << std::setw(9) << leg.b_in_platform[k];
    out << std::setw(11) << leg.offset << "  [" << leg.stroke_min << ", " << leg.stroke_max << "]\n";
  }
  out.unsetf(std::ios::floatfield);
  const RobotLimits& limits = robot.limits;
  if (limits.base_joint_max_deg) out << "base joint max: " << *limits.base_joint_max_deg << " deg\n";
  if (limits.platform_joint_max_deg) out << "platform joint max: " << *limits.platform_joint_max_deg << " deg\n";
  if (limits.leg_min_distance) out << "leg min distance: " << *limits.leg_min_distance << " " << unit << "\n";
  if (const auto& mode = limits.assembly_mode) {
    out << "assembly mode: of the pose [";
    for (int k = 0; k < 6; ++k) out << (k ? ", " : "") << mode->pose[k];
    out << "], det J_IK at least " << mode->min_det_ratio << " of its value there\n";
  }
  static const char* names[6] = {"x", "y", "z", "q1", "q2", "q3"};
  for (const auto& [label, box] : {std::pair{"pose box", &limits.pose_box}, std::pair{"sampling box", &limits.sampling_box}}) {
    if (!*box) continue;
    out << label << ":";
    for (int k = 0; k < 6; ++k) {
      if (const auto& r = (*box)->bounds[k]) out << " " << names[k] << " [" << r->min << ", " << r->max << "]";
    }
    out << "\n";
  }
}

int RunRobot(const std::string& action, const RobotOptions& options, std::ostream& out, std::ostream& err) {
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) {
    if (options.json && action == "check") {
      out << JsonText(nlohmann::json{{"ok", false}, {"error", robot.status().message()}});
    }
    return ReportError(err, "robot " + action, robot.status());
  }
  if (options.json) {
    nlohmann::json j = RobotJson(*robot);
    if (action == "check") j = {{"ok", true}, {"name", robot->name}, {"robot", j}};
    out << JsonText(j);
    return kExitOk;
  }
  if (action == "check") {
    out << "ok: robot '" << robot->name << "' is valid (6 legs, " << LengthUnitName(robot->length_unit) << ")\n";
  } else {
    PrintRobot(*robot, out);
  }
  return kExitOk;
}

void AddAction(CLI::App& parent, const std::string& action, const std::string& help, int* exit_code) {
  auto options = std::make_shared<RobotOptions>();
  CLI::App* sub = parent.add_subcommand(action, help);
  sub->add_option("robot", options->robot, "robot file or preset name")->required();
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunRobot(action, *options, std::cout, std::cerr); });
}

}  // namespace

void AddRobotCommand(CLI::App& app, int* exit_code) {
  CLI::App* robot = app.add_subcommand("robot", "check or show a robot file or preset");
  robot->require_subcommand(1);
  AddAction(*robot, "check", "validate a robot file", exit_code);
  AddAction(*robot, "show", "print a robot's parameters and limits", exit_code);
}

}  // namespace hexcal::cli

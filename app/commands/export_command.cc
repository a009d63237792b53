// hexcal export --robot R --format linuxcnc-hal|robot --out FILE [--machine-unit mm|inch] [--force]
//               [--json | --push --running-robot FILE --ini FILE --controller URL [--yes] [--halcmd PATH]]
//
// Writes a robot's geometry for a controller: `linuxcnc-hal` is the
// `setp genhexkins.base.N.*` / `platform.N.*` lines of LinuxCNC's hexapod
// kinematics, in the machine's linear unit (devices/linuxcnc_geometry.h,
// docs/acquisition.md). Written atomically. --push then loads the whole
// robot into the running machine once the operator confirms: the pins, the
// joints' homes in the INI, homing again (devices/linuxcnc_push.h). A push
// that is refused writes nothing.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/atomic_file.h"
#include "core/robot_io.h"
#include "devices/hal_push.h"
#include "devices/linuxcnc_geometry.h"
#include "devices/linuxcnc_push.h"

namespace hexcal::cli {
namespace {

struct ExportOptions {
  std::string robot, format = "linuxcnc-hal", out, machine_unit = "mm";
  bool force = false, json = false;
  bool push = false, yes = false;  // --push: into the running machine, after a confirmation (or --yes)
  std::string halcmd = "halcmd", running_robot, ini, controller;
};

// The operator's yes: --yes, or "y" typed at a terminal. A push changes a
// moving machine's kinematics, so a script must say --yes.
Status Confirm(const ExportOptions& options, const Robot& robot, std::ostream& out) {
  if (options.yes) return Status::Ok();
  if (!isatty(STDIN_FILENO))
    return Status::BadInput(
        "--push changes the kinematics of a running machine: confirm with --yes "
        "(standard input is not a terminal)");
  out << "Load robot '" << workflow::CommentText(robot.name)
      << "' into the running LinuxCNC? The platform moves to its home switches, the genhexkins pins and the INI's "
         "joint homes change and the machine homes again. [y/N] "
      << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  if (answer == "y" || answer == "Y" || answer == "yes") return Status::Ok();
  return Status::Cancelled();
}

// --push's flags.
Status CheckPushFlags(const ExportOptions& options) {
  for (const auto& [flag, value] : {std::pair{"--running-robot", &options.running_robot},
                                    std::pair{"--ini", &options.ini}, std::pair{"--controller", &options.controller}})
    if (value->empty())
      return Status::BadInput(std::string("--push needs ") + flag +
                              " (the robot the machine runs with, its INI and its linuxcncrsh address: "
                              "the offsets l are the joints' homes, which change in the INI and by homing again)");
  return Status::Ok();
}

// --push's plan (devices/linuxcnc_push.h): every check before anything is written.
StatusOr<workflow::PushPlan> PlanMachinePush(const ExportOptions& options, const Robot& robot,
                                             workflow::PushRequest* request) {
  StatusOr<Robot> running = LoadRobot(options.running_robot);
  if (!running.ok()) return running.status();
  *request = {*running, robot, options.ini, options.running_robot, options.controller, options.halcmd};
  StatusOr<workflow::PushPlan> plan = workflow::PlanPush(*request);
  if (plan.ok() && workflow::MachineUnitName(plan->ini.unit) != std::string(options.machine_unit))
    return Status::BadInput("--machine-unit is " + options.machine_unit + " but the INI's [TRAJ] LINEAR_UNITS is " +
                            workflow::MachineUnitName(plan->ini.unit));
  return plan;
}

int PushToMachine(const workflow::PushRequest& request, const workflow::PushPlan& plan, std::ostream& out,
                  std::ostream& err) {
  StatusOr<workflow::PushReport> pushed = workflow::PushCalibration(request, plan, out);
  if (!pushed.ok()) return ReportError(err, "export", pushed.status());
  char home_error[32];
  std::snprintf(home_error, sizeof home_error, "%.2g", pushed->home_error);
  out << "pushed " << pushed->pins << " pins into the running LinuxCNC and homed again (every joint within "
      << home_error << " " << workflow::MachineUnitName(pushed->unit) << " of its new HOME)\n";
  out << (pushed->ini_changes.empty() ? "the offsets l are unchanged: the INI's joint homes stay\n"
                                      : "the INI's joint homes and limits moved with the offsets l:\n" +
                                            pushed->ini_changes);
  for (const std::string& file : pushed->files) out << "replaced " << file << "\n";
  return kExitOk;
}

void PrintWritten(const ExportOptions& options, const Robot& robot, workflow::MachineUnit unit, std::ostream& out) {
  const bool hal = options.format == "linuxcnc-hal";
  const std::string name = workflow::CommentText(robot.name);
  if (options.json) {
    nlohmann::json json{{"out", options.out},
                        {"format", options.format},
                        {"robot", robot.name},
                        {"length_unit", LengthUnitName(robot.length_unit)}};
    if (hal) json["machine_unit"] = workflow::MachineUnitName(unit);
    out << JsonText(json);
  } else if (hal) {
    out << "wrote " << options.out << ": genhexkins geometry of robot '" << name << "' in "
        << workflow::MachineUnitName(unit) << " (robot file in " << LengthUnitName(robot.length_unit) << ")\n";
  } else {
    out << "wrote " << options.out << ": robot '" << name << "' (" << LengthUnitName(robot.length_unit) << ")\n";
  }
}

// --format linuxcnc-hal: the pins file, then --push. A push is planned and
// confirmed before --out is written: a refused push writes nothing.
int ExportLinuxCncHal(const ExportOptions& options, const Robot& robot, workflow::MachineUnit unit, std::ostream& out,
                      std::ostream& err) {
  workflow::PushRequest request;
  StatusOr<workflow::PushPlan> plan = workflow::PushPlan{};
  if (options.push) {
    if (Status s = CheckPushFlags(options); !s.ok()) return ReportError(err, "export", s);
    plan = PlanMachinePush(options, robot, &request);
    if (!plan.ok()) return ReportError(err, "export", plan.status());
    if (Status s = Confirm(options, robot, out); !s.ok()) {
      if (s.cancelled()) return out << "not pushed: nothing was written and the machine is unchanged\n", kExitFailure;
      return ReportError(err, "export", s);
    }
  }
  if (Status s = WriteFileAtomically(options.out, workflow::GenhexkinsHal(robot, unit)); !s.ok())
    return ReportError(err, "export", s);
  PrintWritten(options, robot, unit, out);
  return options.push ? PushToMachine(request, *plan, out, err) : kExitOk;
}

int RunExport(const ExportOptions& options, std::ostream& out, std::ostream& err) {
  if (options.format != "linuxcnc-hal" && options.format != "robot")
    return ReportError(
        err, "export",
        Status::BadInput("--format: unknown format '" + options.format + "'; accepted: linuxcnc-hal, robot"));
  const std::optional<workflow::MachineUnit> unit = workflow::ParseMachineUnit(options.machine_unit);
  if (!unit)
    return ReportError(err, "export",
                       Status::BadInput("--machine-unit: '" + options.machine_unit +
                                        "' is not a LinuxCNC linear unit; accepted: mm, inch"));
  if (options.push && options.format != "linuxcnc-hal")
    return ReportError(err, "export", Status::BadInput("--push needs --format linuxcnc-hal"));
  // --push asks on the terminal and prints halcmd's answers: not one JSON object.
  if (options.push && options.json) return ReportError(err, "export", Status::BadInput("--json cannot go with --push"));
  if (Status s = CheckOutputFree(options.out, options.force); !s.ok()) return ReportError(err, "export", s);
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) return ReportError(err, "export", robot.status());
  if (options.format == "linuxcnc-hal") {
    if (Status s = workflow::CheckRobotForMachine(*robot); !s.ok()) return ReportError(err, "export", s);
    return ExportLinuxCncHal(options, *robot, *unit, out, err);
  }
  // A preset as a file, e.g. the robot a machine runs with.
  if (Status s = WriteFileAtomically(options.out, RobotToYaml(*robot)); !s.ok()) return ReportError(err, "export", s);
  PrintWritten(options, *robot, *unit, out);
  return kExitOk;
}

}  // namespace

void AddExportCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export", "write a robot's geometry for a controller (LinuxCNC genhexkins HAL)");
  sub->add_option("--robot", options->robot, "robot file or preset name (a calibrated robot file, typically)")
      ->required();
  sub->add_option("--format", options->format, "output format: linuxcnc-hal (genhexkins pins), robot (the robot file)")->capture_default_str();
  sub->add_option("--out", options->out, "file to write")->required();
  sub->add_option("--machine-unit", options->machine_unit,
                  "the machine's [TRAJ] LINEAR_UNITS: mm or inch (lengths are converted from the robot's unit)")
      ->capture_default_str();
  sub->add_flag("--force", options->force, "overwrite an existing --out file");
  sub->add_flag("--json", options->json, "print one JSON object on stdout (not with --push)");
  sub->add_flag("--push", options->push,
                "also load the robot into the running LinuxCNC (pins, INI joint homes, homing again), after a "
                "confirmation");
  sub->add_flag("--yes", options->yes, "confirm --push without asking (scripts)");
  sub->add_option("--halcmd", options->halcmd, "the halcmd to run for --push")->capture_default_str();
  sub->add_option("--running-robot", options->running_robot,
                  "with --push: the robot file the machine runs with now (replaced by --robot after the push)");
  sub->add_option("--ini", options->ini, "with --push: the machine's INI (its joint homes and limits are updated)");
  sub->add_option("--controller", options->controller,
                  "with --push: the machine's linuxcncrsh, linuxcnc://HOST:PORT (to home it again)");
  sub->callback([=] { *exit_code = RunExport(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli
